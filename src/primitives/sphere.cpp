// Sphere (ID 1): radius; centre. The points x with |x - c| = r (section 2.2 of the original).
#include <cmath>

#include "primitives/sphere_test.h"
#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::sphere {

namespace {

struct Sphere {
    double radius;
    SphereParameters test;  // centre and r^2 (precomputed, as the original suggests)
};

ShapeData read(SceneReader& reader) {
    const double radius = reader.positive("sphere radius");
    const Vec3 centre = reader.vec3("sphere centre");
    return reader.shape_data(Sphere{radius, {centre, radius * radius}});
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    return sphere_hit(static_cast<const Sphere*>(shape)->test, ray, range, hit);
}

SphereParameters parameters(const void* shape) { return static_cast<const Sphere*>(shape)->test; }

Vec3 normal(const void* shape, const Vec3& point, const Hit&) {
    const auto& s = *static_cast<const Sphere*>(shape);
    return normalized(point - s.test.centre);
}

Bounds bounds(const void* shape) {
    const auto& s = *static_cast<const Sphere*>(shape);
    const Vec3 r{s.radius, s.radius, s.radius};
    return {s.test.centre - r, s.test.centre + r};
}

bool inside(const void* shape, const Vec3& point) {
    const auto& s = *static_cast<const Sphere*>(shape);
    return length_squared(point - s.test.centre) < s.test.radius_squared;
}

}  // namespace

extern const PrimitiveFunctions functions{.read = read,
                                          .intersect = intersect,
                                          .normal = normal,
                                          .bounds = bounds,
                                          .inside = inside,
                                          .sphere = parameters};

}  // namespace rt::sphere
