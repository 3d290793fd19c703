// The camera of section 1.6 of the original: an eye, a point looked at, and two vectors that
// span the image plane.
#pragma once

#include <optional>

#include "rt/ray.h"

namespace rt {

struct Viewer {
    Vec3 eye;
    Vec3 look_at;
    Vec3 x;  // half-width of the image plane, horizontally
    Vec3 y;  // half-height, vertically; neither need be unit nor perpendicular
    int xres = 0;
    int yres = 0;

    // The ray through raster position (px, py): px in [0, xres], py in [0, yres], y down.
    // Integer positions are the pixel corners, exactly as the original prints the formula.
    Ray primary_ray(double px, double py) const {
        const Vec3 centre = eye + normalized(look_at - eye);
        const double alpha = (2 * px - xres) / xres;
        const double beta = -(2 * py - yres) / yres;
        return {eye, normalized(centre + alpha * x + beta * y - eye)};
    }
};

// Pixels are square when xres : yres is |x| : |y|. When they are not (to within rounding a
// side to a whole pixel), the height that would make them square at this width.
std::optional<int> square_pixel_height(const Viewer& v);

}  // namespace rt
