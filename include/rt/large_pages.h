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
#include <utility>

namespace rt {

// Arrays this large or larger are given whole 2 MiB pages; smaller ones come from operator
// new. At 256 KiB a huge page, zeroed once, costs a sixth of the 64 faults of 4 KiB pages
// it replaces (gears-100's hierarchy built in 3 ms instead of 8, its scene read in 9 instead
// of 11); smaller, the memory a partly used page wastes would outweigh the time.
inline constexpr std::size_t kLargeArrayBytes = std::size_t{256} << 10;

// `bytes` of uninitialised memory aligned to at least `alignment` (a power of two, at most
// 4096); throws std::bad_alloc when there is none.
void* allocate_array(std::size_t bytes, std::size_t alignment);
// Whether allocate_array's memory of this size comes zeroed (fresh pages from the kernel):
// then an array that must start at zero need not be written before its first use, and the
// threads that first write it share the zeroing of its pages.
bool arrays_come_zeroed(std::size_t bytes) noexcept;
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

// An allocator that leaves elements default-initialised: for a trivial type, a vector's
// resize() then neither writes them nor touches their pages. Large arrays get 2 MiB pages
// where the kernel offers them.
template <class T>
struct UninitializedAllocator : LargeArrayAllocator<T> {
    template <class U>
    struct rebind {
        using other = UninitializedAllocator<U>;
    };
    UninitializedAllocator() = default;
    template <class U>
    explicit UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}

    template <class U>
    void construct(U* p) noexcept {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

}  // namespace rt
