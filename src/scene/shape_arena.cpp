#include "rt/shape_arena.h"

#include <algorithm>

#include "rt/large_pages.h"

namespace rt {

namespace {

// The first block is small, so that a scene of a few objects takes little. The next are
// whole 2 MiB pages (rt/large_pages.h), 2 MiB and then 4: a scene that outgrows the first
// touches its fresh memory a huge page at a time, not in hundreds of 4 KiB faults.
constexpr std::size_t kFirstBlock = std::size_t{16} << 10;
constexpr std::size_t kSecondBlock = std::size_t{2} << 20;
constexpr std::size_t kLargestBlock = std::size_t{4} << 20;
constexpr std::size_t kBlockAlignment = 64;
static_assert(ShapeArena::kOwnBlockFrom <= kLargestBlock);

}  // namespace

ShapeArena::~ShapeArena() {
    for (const Block& b : blocks_) free_array(b.data, b.size, kBlockAlignment);
    for (const Block& b : alone_) free_array(b.data, b.size, kBlockAlignment);
}

void* ShapeArena::place(std::size_t bytes, std::size_t alignment) {
    if (!blocks_.empty()) {
        const std::size_t start = (used_ + alignment - 1) & ~(alignment - 1);
        if (start + bytes <= blocks_.back().size) {
            used_ = start + bytes;
            return blocks_.back().data + start;
        }
    }
    if (bytes > kOwnBlockFrom) {
        alone_.reserve(alone_.size() + 1);  // so that the push below cannot throw and leak
        auto* data = static_cast<std::byte*>(allocate_array(bytes, kBlockAlignment));
        alone_.push_back({data, bytes});
        return data;
    }
    blocks_.reserve(blocks_.size() + 1);
    std::size_t size = blocks_.empty()       ? kFirstBlock
                       : blocks_.size() == 1 ? kSecondBlock
                                             : std::min(2 * blocks_.back().size, kLargestBlock);
    while (size < bytes) size *= 2;  // at most kLargestBlock, since bytes <= kOwnBlockFrom
    auto* data = static_cast<std::byte*>(allocate_array(size, kBlockAlignment));
    blocks_.push_back({data, size});
    used_ = bytes;
    return data;
}

}  // namespace rt
