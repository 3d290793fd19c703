// Where a scene's small primitives keep their parameters: blocks of many shapes, each block
// one allocation (in 2 MiB pages once blocks are large, rt/large_pages.h), instead of one
// allocation per shape. A million spheres made a million small allocations from the heap,
// each touching fresh 4 KiB pages as the scene was read; in blocks, spheres-1m's read takes
// 0.14 s instead of 0.31-0.37 (docs/performance.md, "Fresh memory").
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

#include "rt/primitive.h"

namespace rt {

class ShapeArena {
  public:
    ShapeArena() = default;
    ~ShapeArena();
    ShapeArena(const ShapeArena&) = delete;
    ShapeArena& operator=(const ShapeArena&) = delete;

    // Room for `bytes` aligned to `alignment` (at most 64), valid as long as the arena.
    // Any size: one larger than kOwnBlockFrom is given a block of its own (a polygon with
    // a hundred thousand vertices), so that the block being filled keeps its free room.
    void* place(std::size_t bytes, std::size_t alignment);

    // make_shape_data places a value this large or smaller; others are allocated alone.
    static constexpr std::size_t kLargestShape = 256;
    static constexpr std::size_t kOwnBlockFrom = std::size_t{1} << 20;

  private:
    struct Block {
        std::byte* data;
        std::size_t size;
    };
    std::vector<Block> blocks_;  // the last is being filled
    std::size_t used_ = 0;       // bytes of the last block in use
    std::vector<Block> alone_;   // each holding one shape larger than kOwnBlockFrom
};

// An allocator from an arena, for std::allocate_shared: the object and its shared count are
// placed together in the arena, and the count keeps the arena alive (the allocator's copy in
// it shares the arena's ownership), so an object may have a destructor of its own. Nothing
// is given back before the arena goes.
template <class T>
struct ArenaAllocator {
    using value_type = T;
    std::shared_ptr<ShapeArena> arena;

    explicit ArenaAllocator(std::shared_ptr<ShapeArena> from) noexcept : arena(std::move(from)) {}
    template <class U>
    explicit ArenaAllocator(const ArenaAllocator<U>& other) noexcept : arena(other.arena) {}

    T* allocate(std::size_t n) {
        if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
        return static_cast<T*>(arena->place(n * sizeof(T), alignof(T)));
    }
    void deallocate(T*, std::size_t) noexcept {}
    template <class U>
    bool operator==(const ArenaAllocator<U>& other) const noexcept {
        return arena == other.arena;
    }
};

// The arena `arena` points to, made on first use.
inline ShapeArena& arena_made(std::shared_ptr<ShapeArena>& arena) {
    if (!arena) arena = std::make_shared<ShapeArena>();
    return *arena;
}

// A primitive's parameters as a shape holds them. One whose destructor does nothing (a
// sphere's, a triangle's, a cylinder's) is placed in `arena`, created on first use, and the
// shape shares the arena's ownership: the arena lives as long as any shape in it. Others (a
// polygon's, which own memory of their own) are allocated alone.
template <class T>
ShapeData make_shape_data(std::shared_ptr<ShapeArena>& arena, T value) {
    if constexpr (std::is_trivially_destructible_v<T> && sizeof(T) <= ShapeArena::kLargestShape &&
                  alignof(T) <= 64) {
        const T* placed =
            ::new (arena_made(arena).place(sizeof(T), alignof(T))) T(std::move(value));
        return ShapeData(arena, placed);
    } else {
        return std::make_shared<const T>(std::move(value));
    }
}

}  // namespace rt
