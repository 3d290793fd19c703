#include "render/primary_mask.h"

#include <algorithm>
#include <cmath>

#include "render/projection.h"

namespace rt {

namespace {

// A box is marked two pixels wider on each side than its corners' projections (each moved
// out by a bound on its own rounding): a pixel's rays pass within half a pixel of its
// position, and the tracer's rounding of their directions may move them by at most
// Projection::kMaxRayError pixels (checked), which leaves more than a pixel to spare.
constexpr double kWidening = 2;

}  // namespace

PrimaryMask::PrimaryMask(const Viewer& viewer, std::span<const Bounds> boxes)
    : PrimaryMask(viewer, boxes, {0, 0, viewer.xres, viewer.yres}) {}

PrimaryMask::PrimaryMask(const Viewer& viewer, std::span<const Bounds> boxes, const PixelRect& area)
    : area_(area) {
    if (viewer.xres <= 0 || viewer.yres <= 0 || area.empty()) return;
    const Projection projection(viewer);
    if (!projection.usable()) return;
    const auto tiles_across = [](int pixels) {
        return (static_cast<std::size_t>(pixels) + (1u << kTileShift) - 1) >> kTileShift;
    };
    columns_ = tiles_across(area.width());
    const std::size_t rows = tiles_across(area.height());
    tiles_.assign(columns_ * rows, 0);
    for (const Bounds& box : boxes) {
        Rectangle r;
        if (!project_box(projection, box, r)) {
            tiles_ = {};
            return;
        }
        if (!(r.x0 <= r.x1)) continue;  // wholly behind the eye
        // Raster positions within the area, counted from its corner.
        const auto [first_column, last_column] =
            tile_span(r.x0 - area.x0, r.x1 - area.x0, kWidening, area.width(), kTileShift);
        const auto [first_row, last_row] =
            tile_span(r.y0 - area.y0, r.y1 - area.y0, kWidening, area.height(), kTileShift);
        for (long row = first_row; row <= last_row; ++row)
            for (long column = first_column; column <= last_column; ++column)
                tiles_[static_cast<std::size_t>(row) * columns_ +
                       static_cast<std::size_t>(column)] = 1;
    }
    everywhere_ = false;
    const auto tile_size = [](std::size_t tile, int pixels) {
        return std::min<std::size_t>(std::size_t{1} << kTileShift,
                                     static_cast<std::size_t>(pixels) - (tile << kTileShift));
    };
    for (std::size_t row = 0; row < rows; ++row)
        for (std::size_t column = 0; column < columns_; ++column)
            if (tiles_[row * columns_ + column] == 0)
                spared_ += tile_size(column, area.width()) * tile_size(row, area.height());
}

}  // namespace rt
