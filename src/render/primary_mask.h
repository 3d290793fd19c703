// Which pixels' primary rays may meet a bounded object at all. The boxes of a cut across the
// object hierarchy (ObjectIndex::outline) are projected from the eye onto the image plane,
// and every 4 x 4 tile of pixels that one of them may cover is marked. A primary ray through
// an unmarked tile misses every box, and so every bounded object (a hit lies in its object's
// box, which lies in the cut's), and needs asking only the unbounded ones: the hierarchy's
// walk, whose preparation and root test are most of what a ray that hits nothing costs, is
// skipped. The answer is the walk's to the bit, so no image changes.
//
// The projection is computed in double with a bound on its rounding (projection.h), and a box
// is marked two pixels wider on each side than its corners' projections, which covers both
// that rounding and the primary rays' own (within half a pixel of their pixel's position: the
// original's ray through the corner, or a sample of its grid). A box reaching behind the eye
// is cut where primary rays can first meet anything. Where the bound is not met (a camera
// whose vectors are nearly coplanar, numbers too large), every pixel is marked: the mask only
// ever saves work.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "rt/raster.h"
#include "rt/ray.h"
#include "rt/viewer.h"

namespace rt {

class PrimaryMask {
  public:
    // Every pixel marked.
    PrimaryMask() = default;
    // The pixels of `area` (of the viewer's image; the whole image by default) whose primary
    // rays may cross one of `boxes`. Pixels outside the area are all marked: a render of a
    // region makes the mask of the region alone, at the region's cost.
    PrimaryMask(const Viewer& viewer, std::span<const Bounds> boxes);
    PrimaryMask(const Viewer& viewer, std::span<const Bounds> boxes, const PixelRect& area);

    // Whether a primary ray of pixel (x, y) may cross one of the boxes.
    bool may_hit(int x, int y) const {
        if (everywhere_ || x < area_.x0 || y < area_.y0 || x >= area_.x1 || y >= area_.y1)
            return true;
        const auto column = static_cast<std::size_t>(x - area_.x0) >> kTileShift;
        const auto row = static_cast<std::size_t>(y - area_.y0) >> kTileShift;
        return tiles_[row * columns_ + column] != 0;
    }
    // Whether every pixel is marked (no ray is spared the walk).
    bool everywhere() const { return everywhere_; }
    // How many of the area's pixels are not marked.
    std::size_t pixels_spared() const { return spared_; }

  private:
    static constexpr int kTileShift = 2;  // tiles of 4 x 4 pixels

    bool everywhere_ = true;
    PixelRect area_;           // the pixels the tiles cover
    std::size_t columns_ = 0;  // tiles per row
    std::vector<std::uint8_t> tiles_;
    std::size_t spared_ = 0;
};

}  // namespace rt
