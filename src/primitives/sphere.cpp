// Sphere (ID 1): radius; centre. The points x with |x - c| = r (section 2.2 of the original).
#include <cmath>

#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::sphere {

namespace {

struct Sphere {
    double radius;
    double radius_squared;  // precomputed, as the original suggests
    Vec3 centre;
};

ShapeData read(SceneReader& reader) {
    const double radius = reader.positive("sphere radius");
    const Vec3 centre = reader.vec3("sphere centre");
    return std::make_shared<const Sphere>(Sphere{radius, radius * radius, centre});
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    const auto& s = *static_cast<const Sphere*>(shape);
    // With a unit direction the quadratic is t^2 + 2bt + c = 0.
    const Vec3 oc = ray.origin - s.centre;
    const double b = dot(oc, ray.direction);
    // r^2 - |oc - b d|^2 is the discriminant without the cancellation of b^2 - c when the
    // sphere is far away and small.
    const Vec3 perpendicular = oc - b * ray.direction;
    const double discriminant = s.radius_squared - length_squared(perpendicular);
    if (discriminant < 0) return false;
    const double c = length_squared(oc) - s.radius_squared;
    // The root of larger magnitude first, then the other as c / q: no cancellation.
    const double q = -b - std::copysign(std::sqrt(discriminant), b);
    double near = q;
    double far = q != 0 ? c / q : 0;
    if (near > far) std::swap(near, far);
    const double t = range.contains(near) ? near : far;
    if (!range.contains(t)) return false;
    hit.t = t;
    hit.part = 0;
    return true;
}

Vec3 normal(const void* shape, const Vec3& point, const Hit&) {
    const auto& s = *static_cast<const Sphere*>(shape);
    return normalized(point - s.centre);
}

Bounds bounds(const void* shape) {
    const auto& s = *static_cast<const Sphere*>(shape);
    const Vec3 r{s.radius, s.radius, s.radius};
    return {s.centre - r, s.centre + r};
}

bool inside(const void* shape, const Vec3& point) {
    const auto& s = *static_cast<const Sphere*>(shape);
    return length_squared(point - s.centre) < s.radius_squared;
}

}  // namespace

extern const PrimitiveFunctions functions{
    .read = read, .intersect = intersect, .normal = normal, .bounds = bounds, .inside = inside};

}  // namespace rt::sphere
