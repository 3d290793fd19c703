// Cylinder (ID 9): radius; start; finish; point on axis c; axis a. The points at distance r
// from the axis line (section 2.9 of the original), kept where
// start <= (x - c).a / |a|^2 <= finish. It is open: there are no caps.
#include <cmath>

#include "primitives/axial.h"
#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::cylinder {

namespace {

struct Cylinder {
    AxialExtent extent;
    double radius;
    double radius_squared;
};

ShapeData read(SceneReader& reader) {
    const double radius = reader.positive("cylinder radius");
    const AxialExtent extent = read_axial_extent(reader, "cylinder", "point on axis");
    return reader.shape_data(Cylinder{extent, radius, radius * radius});
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    const auto& cyl = *static_cast<const Cylinder*>(shape);
    const Vec3& axis = cyl.extent.axis;
    // Only the parts across the axis matter for the distance from it.
    const AxialRay r(cyl.extent, ray);
    const Vec3& w = r.w;
    const Vec3& w_across = r.w_across;
    const Vec3& d_across = r.d_across;
    // A t^2 + 2 B t + C = 0, with A = |d_across|^2 rather than the original's 1 - (d.a)^2,
    // which cancels for rays near the axis.
    const double a = length_squared(d_across);
    // A ray parallel to the axis never crosses the surface: it stays inside or outside.
    if (a == 0) return false;
    const double b = dot(w_across, d_across);
    const double c = length_squared(w_across) - cyl.radius_squared;
    // B^2 - A C = A r^2 - ((w x d).a)^2: the ray's distance from the axis enters directly
    // instead of as the difference of two large products.
    const double s = dot(cross(w, ray.direction), axis);
    const double discriminant = a * cyl.radius_squared - s * s;
    if (!(discriminant >= 0)) return false;
    return nearest_kept_root(solve_quadratic(a, b, c, discriminant), range, cyl.extent, r, hit);
}

Vec3 normal(const void* shape, const Vec3& point, const Hit&) {
    const auto& cyl = *static_cast<const Cylinder*>(shape);
    const Vec3& axis = cyl.extent.axis;
    // The part of x - c across the axis points straight away from it.
    const Vec3 v = point - cyl.extent.origin;
    return normalized(v - dot(v, axis) * axis);
}

Bounds bounds(const void* shape) {
    const auto& cyl = *static_cast<const Cylinder*>(shape);
    return axial_bounds(cyl.extent, cyl.radius, cyl.radius);
}

}  // namespace

extern const PrimitiveFunctions functions{
    .read = read, .intersect = intersect, .normal = normal, .bounds = bounds};

}  // namespace rt::cylinder
