#include "rt/shape_arena.h"

#include <algorithm>

#include "rt/large_pages.h"

namespace rt {

namespace {

// Blocks start small, so that a scene of a few objects takes little, and double up to a
// size that 2 MiB pages back.
constexpr std::size_t kFirstBlock = std::size_t{16} << 10;
constexpr std::size_t kLargestBlock = std::size_t{4} << 20;
constexpr std::size_t kBlockAlignment = 64;

}  // namespace

ShapeArena::~ShapeArena() {
    for (const Block& b : blocks_) free_array(b.data, b.size, kBlockAlignment);
}

void* ShapeArena::place(std::size_t bytes, std::size_t alignment) {
    if (!blocks_.empty()) {
        const std::size_t start = (used_ + alignment - 1) & ~(alignment - 1);
        if (start + bytes <= blocks_.back().size) {
            used_ = start + bytes;
            return blocks_.back().data + start;
        }
    }
    const std::size_t size =
        blocks_.empty() ? kFirstBlock : std::min(2 * blocks_.back().size, kLargestBlock);
    blocks_.reserve(blocks_.size() + 1);  // so that the push below cannot throw and leak
    auto* data = static_cast<std::byte*>(allocate_array(size, kBlockAlignment));
    blocks_.push_back({data, size});
    used_ = bytes;
    return data;
}

}  // namespace rt
