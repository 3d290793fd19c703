// Memory for large arrays (the hierarchies', a mesh's, the raster) in the kernel's 2 MiB pages
// where it offers them (Linux's transparent huge pages, asked for with madvise). A fresh page is
// zeroed by the kernel on its first touch, and on a virtual machine each 4 KiB fault is a trip
// through the hypervisor: on the machine these figures come from, touching 256 MB took 0.60-0.70 s
// in 4 KiB pages and 0.02-0.37 s in 2 MiB ones, and spheres-1m's index build (once its memory
// was not new to the machine) went from 0.71 to 0.34 s (docs/performance.md, "Fresh memory").
// Fewer pages also means fewer TLB misses while rendering. Elsewhere, and for small arrays,
// this is operator new.
#pragma once

#include <cstddef>
#include <memory>
#include <new>

namespace rt {

// Arrays this large or larger are given whole 2 MiB pages; smaller ones come from operator
// new, where a partly used huge page would waste more than it saves.
inline constexpr std::size_t kLargeArrayBytes = std::size_t{2} << 20;

// `bytes` of uninitialised memory aligned to at least `alignment` (a power of two, at most
// 4096); throws std::bad_alloc when there is none.
void* allocate_array(std::size_t bytes, std::size_t alignment);
// Frees what allocate_array returned, given the same size and alignment.
void free_array(void* memory, std::size_t bytes, std::size_t alignment) noexcept;

// std::allocator with its memory from allocate_array: a vector that grows large is given
// huge pages.
template <class T>
struct LargeArrayAllocator : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = LargeArrayAllocator<U>;
    };
    LargeArrayAllocator() = default;
    template <class U>
    explicit LargeArrayAllocator(const LargeArrayAllocator<U>&) noexcept {}

    T* allocate(std::size_t n) {
        if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
        return static_cast<T*>(allocate_array(n * sizeof(T), alignof(T)));
    }
    void deallocate(T* p, std::size_t n) noexcept { free_array(p, n * sizeof(T), alignof(T)); }
};

}  // namespace rt
