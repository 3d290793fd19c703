#include "rt/large_pages.h"

#include <new>

#if defined(__linux__)
#include <sys/mman.h>

#include <cstdint>
#endif

namespace rt {

namespace {

void* allocate_small(std::size_t bytes, std::size_t alignment) {
    return alignment > __STDCPP_DEFAULT_NEW_ALIGNMENT__
               ? ::operator new (bytes, std::align_val_t{alignment})
               : ::operator new(bytes);
}

void free_small(void* memory, std::size_t alignment) noexcept {
    if (alignment > __STDCPP_DEFAULT_NEW_ALIGNMENT__)
        ::operator delete (memory, std::align_val_t{alignment});
    else
        ::operator delete(memory);
}

}  // namespace

#if defined(__linux__)
namespace {

constexpr std::size_t kHugePage = std::size_t{2} << 20;

std::size_t whole_huge_pages(std::size_t bytes) {
    return (bytes + kHugePage - 1) & ~(kHugePage - 1);
}

}  // namespace

void* allocate_array(std::size_t bytes, std::size_t alignment) {
    if (bytes < kLargeArrayBytes) return allocate_small(bytes, alignment);
    const std::size_t size = whole_huge_pages(bytes);
    if (size < bytes || size + kHugePage < size) throw std::bad_alloc();
    // One huge page more than needed, so that a run of whole huge pages can be cut from it
    // (the kernel backs only aligned 2 MiB ranges with huge pages); the rest is given back.
    void* const mapped =
        mmap(nullptr, size + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (mapped == MAP_FAILED) throw std::bad_alloc();
    const auto start = reinterpret_cast<std::uintptr_t>(mapped);
    const std::uintptr_t aligned = (start + kHugePage - 1) & ~std::uintptr_t{kHugePage - 1};
    if (aligned > start) munmap(mapped, aligned - start);
    const std::uintptr_t tail = aligned + size;
    const std::uintptr_t end = start + size + kHugePage;
    if (end > tail) munmap(reinterpret_cast<void*>(tail), end - tail);
    // Only advice: where the kernel has no huge pages to give (or they are switched off),
    // these are ordinary pages and nothing else changes.
    madvise(reinterpret_cast<void*>(aligned), size, MADV_HUGEPAGE);
    return reinterpret_cast<void*>(aligned);
}

bool arrays_come_zeroed(std::size_t bytes) noexcept { return bytes >= kLargeArrayBytes; }

void free_array(void* memory, std::size_t bytes, std::size_t alignment) noexcept {
    if (memory == nullptr) return;
    if (bytes < kLargeArrayBytes) return free_small(memory, alignment);
    munmap(memory, whole_huge_pages(bytes));
}

#else

void* allocate_array(std::size_t bytes, std::size_t alignment) {
    return allocate_small(bytes, alignment);
}

bool arrays_come_zeroed(std::size_t) noexcept { return false; }

void free_array(void* memory, std::size_t, std::size_t alignment) noexcept {
    free_small(memory, alignment);
}

#endif

}  // namespace rt
