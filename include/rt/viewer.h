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
    Ray primary_ray(double px, double py) const { return primary_ray(px, py, plane_centre()); }
    // The same with the image plane's centre given (plane_centre(), which every ray shares:
    // the tracer computes it once instead of a square root and a division per ray).
    Ray primary_ray(double px, double py, const Vec3& centre) const {
        return ray_through(alpha(px), beta(py), centre);
    }
    // The formula's two parts: the image plane's coordinates of raster position px and py
    // (each from -1 to 1), and the ray through the point they give.
    double alpha(double px) const { return (2 * px - xres) / xres; }
    double beta(double py) const { return -(2 * py - yres) / yres; }
    Ray ray_through(double alpha, double beta, const Vec3& centre) const {
        return {eye, normalized(centre + alpha * x + beta * y - eye)};
    }
    // The image plane's centre: one unit from the eye towards the point looked at.
    Vec3 plane_centre() const { return eye + normalized(look_at - eye); }
};

// Pixels are square when xres : yres is |x| : |y|. When they are not (to within rounding a
// side to a whole pixel), the height that would make them square at this width.
std::optional<int> square_pixel_height(const Viewer& v);

}  // namespace rt
