// Sphere (ID 1): radius; centre. The points x with |x - c| = r (section 2.2 of the original).
#include <cmath>

#include "primitives/sphere_test.h"
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
    double t = 0;
    if (!sphere_crossing({s.centre, s.radius_squared}, ray, range, t)) return false;
    hit.t = t;
    hit.part = 0;
    return true;
}

SphereParameters parameters(const void* shape) {
    const auto& s = *static_cast<const Sphere*>(shape);
    return {s.centre, s.radius_squared};
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
    .read = read,
    .intersect = intersect,
    .normal = normal,
    .bounds = bounds,
    .inside = inside,
    .sphere = parameters};

}  // namespace rt::sphere
