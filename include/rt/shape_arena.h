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

    // Room for `bytes` (at most kLargestShape) aligned to `alignment` (at most 64), valid
    // as long as the arena.
    void* place(std::size_t bytes, std::size_t alignment);

    static constexpr std::size_t kLargestShape = 256;

  private:
    struct Block {
        std::byte* data;
        std::size_t size;
    };
    std::vector<Block> blocks_;
    std::size_t used_ = 0;  // bytes of the last block in use
};

// A primitive's parameters as a shape holds them. One whose destructor does nothing (a
// sphere's, a triangle's, a cylinder's) is placed in `arena`, created on first use, and the
// shape shares the arena's ownership: the arena lives as long as any shape in it. Others (a
// polygon's, which own memory of their own) are allocated alone.
template <class T>
ShapeData make_shape_data(std::shared_ptr<ShapeArena>& arena, T value) {
    if constexpr (std::is_trivially_destructible_v<T> && sizeof(T) <= ShapeArena::kLargestShape &&
                  alignof(T) <= 64) {
        if (!arena) arena = std::make_shared<ShapeArena>();
        const T* placed = ::new (arena->place(sizeof(T), alignof(T))) T(std::move(value));
        return ShapeData(arena, placed);
    } else {
        return std::make_shared<const T>(std::move(value));
    }
}

}  // namespace rt
