// What the cone and the cylinder share: an axis through a point, and the stretch of it they
// keep. Both read "start; finish; point (3); axis (3)" and keep the points x with
// start <= (x - c).a / |a|^2 <= finish, so the extent is measured in multiples of the axis
// vector's length (the original's cone from 0 to 2 along (0,-5,0) runs 10 units).
#pragma once

#include <cmath>
#include <string>

#include "primitives/planar.h"
#include "rt/reader.h"

namespace rt {

struct AxialExtent {
    Vec3 origin;      // c: the apex of a cone, a point on a cylinder's axis
    Vec3 axis;        // a / |a|
    double near = 0;  // start |a|: the extent as distances along the unit axis
    double far = 0;   // finish |a|

    // Distance along the unit axis from the origin to a point.
    double height(const Vec3& point) const { return dot(point - origin, axis); }
    bool keeps(double h) const { return h >= near && h <= far; }
};

// A ray seen from the axis: the offset of its origin from the axis point, and that offset and
// its direction split into parts along and across the unit axis.
struct AxialRay {
    Vec3 w;  // ray origin - axis point
    double w_along, d_along;
    Vec3 w_across, d_across;

    AxialRay(const AxialExtent& e, const Ray& ray)
        : w(ray.origin - e.origin),
          w_along(dot(w, e.axis)),
          d_along(dot(ray.direction, e.axis)),
          w_across(w - w_along * e.axis),
          d_across(ray.direction - d_along * e.axis) {}
};

// Reads start, finish, point and axis. `name` ("cone") prefixes each field in messages and
// `point_name` ("apex") names the point.
inline AxialExtent read_axial_extent(SceneReader& reader, const std::string& name,
                                     const std::string& point_name) {
    const double start = reader.number(name + " start");
    const Location finish_at = reader.next_location();
    const double finish = reader.number(name + " finish");
    if (!(start < finish))
        reader.fail(finish_at, name + " finish must be greater than start " + format_number(start) +
                                   ", got " + format_number(finish));
    const Vec3 origin = reader.vec3(name + " " + point_name);
    const Location axis_at = reader.next_location();
    double len = 0;
    const Vec3 a = reader.direction(name + " axis", &len);
    const AxialExtent extent{origin, a, start * len, finish * len};
    // The extent in distances must stay finite and non-empty after scaling by |a|.
    if (!std::isfinite(extent.near) || !std::isfinite(extent.far) || !(extent.near < extent.far))
        reader.fail(axis_at, name + " start and finish times the axis length (" +
                                 format_number(len) + ") must be finite and distinct");
    return extent;
}

// The roots of A t^2 + 2 B t + C = 0 in increasing order, given the discriminant B^2 - A C
// (which each caller computes in a form without cancellation). The larger-magnitude root
// is q / A and the other C / q, so neither cancels; when A is zero (a ray
// parallel to a cone's side) q / A is infinite and C / q is the one real root. Roots that
// do not exist come out infinite or NaN, which no Interval contains.
struct QuadraticRoots {
    double first, second;
};
inline QuadraticRoots solve_quadratic(double a, double b, double c, double discriminant) {
    const double q = -(b + std::copysign(std::sqrt(discriminant), b));
    const double r1 = q / a;
    const double r2 = c / q;
    return r1 < r2 ? QuadraticRoots{r1, r2} : QuadraticRoots{r2, r1};
}

// The nearer root that is in range and on the kept part of the surface. A root on the
// clipped-away part does not hide the other: through the open end of a cone or cylinder its
// far wall shows.
inline bool nearest_kept_root(const QuadraticRoots& roots, Interval range,
                              const AxialExtent& extent, const AxialRay& r, Hit& hit) {
    for (const double t : {roots.first, roots.second}) {
        if (!range.contains(t) || !extent.keeps(r.w_along + t * r.d_along)) continue;
        hit = {t, 0};
        return true;
    }
    return false;
}

// The bounds of an axial surface: the box around its two end circles, whose radii are
// given. Every circle between lies in the convex hull of the two, so the box holds it.
inline Bounds axial_bounds(const AxialExtent& e, double near_radius, double far_radius) {
    Bounds box = disk_bounds(e.origin + e.near * e.axis, e.axis, near_radius);
    const Bounds end = disk_bounds(e.origin + e.far * e.axis, e.axis, far_radius);
    box.expand(end.min);
    box.expand(end.max);
    return box;
}

}  // namespace rt
