#include "scene/affine_frame.h"

#include <cmath>

#include "rt/reader.h"

namespace rt {

namespace {

// One term F_ij [lo, hi] of the interval sum in to_world_bounds.
void add_scaled_interval(double factor, double lo, double hi, double& sum_lo, double& sum_hi) {
    if (factor == 0) return;  // 0 * infinity would be NaN; the term is exactly 0
    const double a = factor * lo, b = factor * hi;
    sum_lo += std::fmin(a, b);
    sum_hi += std::fmax(a, b);
}

bool is_finite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

Bounds AffineFrame::to_world_bounds(const Bounds& local) const {
    Bounds world;
    double* lo[3] = {&world.min.x, &world.min.y, &world.min.z};
    double* hi[3] = {&world.max.x, &world.max.y, &world.max.z};
    for (int i = 0; i < 3; ++i) {
        *lo[i] = *hi[i] = origin[i];
        add_scaled_interval(x[i], local.min.x, local.max.x, *lo[i], *hi[i]);
        add_scaled_interval(y[i], local.min.y, local.max.y, *lo[i], *hi[i]);
        add_scaled_interval(z[i], local.min.z, local.max.z, *lo[i], *hi[i]);
    }
    return world;
}

std::string frame_problem(const Vec3& x, const Vec3& y, const Vec3& z) {
    const double det = dot(x, cross(y, z));
    const double volume_bound = length(x) * length(y) * length(z);
    if (!std::isfinite(det) || !std::isfinite(volume_bound))
        return "is too large: its determinant overflows";
    if (!(std::fabs(det) > kSingularFrameTolerance * volume_bound))
        return "is singular: X, Y and Z are linearly dependent or one is zero (det F = " +
               format_number(det) + ")";
    if (!is_finite(cross(y, z) / det) || !is_finite(cross(z, x) / det) ||
        !is_finite(cross(x, y) / det))
        return "is too small: its inverse overflows";
    return "";
}

AffineFrame make_affine_frame(const Vec3& origin, const Vec3& x, const Vec3& y, const Vec3& z) {
    // The rows of F^-1 are the cross products of pairs of columns over the determinant.
    const double det = dot(x, cross(y, z));
    return {origin, x, y, z, cross(y, z) / det, cross(z, x) / det, cross(x, y) / det};
}

AffineFrame read_affine_frame(SceneReader& reader, std::string_view what) {
    const std::string name(what);
    const Vec3 origin = reader.vec3(name + " origin O");
    const Location axes_at = reader.next_location();
    const Vec3 x = reader.vec3(name + " axis X");
    const Vec3 y = reader.vec3(name + " axis Y");
    const Vec3 z = reader.vec3(name + " axis Z");
    const std::string problem = frame_problem(x, y, z);
    if (!problem.empty()) reader.fail(axes_at, name + " frame " + problem);
    return make_affine_frame(origin, x, y, z);
}

}  // namespace rt
