#include "rt/viewer.h"

#include <cmath>

namespace rt {

std::optional<int> square_pixel_height(const Viewer& v) {
    const double aspect = length(v.x) / length(v.y);  // width over height of the image plane
    const double square_height = v.xres / aspect;
    const double square_width = v.yres * aspect;
    // Either side rounded to whole pixels is square enough.
    if (std::lround(square_height) == v.yres || std::lround(square_width) == v.xres)
        return std::nullopt;
    return static_cast<int>(std::max(1L, std::lround(square_height)));
}

}  // namespace rt
