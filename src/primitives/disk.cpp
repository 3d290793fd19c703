// Disk (ID 3): centre; normal; radius. The plane through the centre, kept within the radius
// (section 2.4 of the original).
#include "primitives/planar.h"
#include "primitives/primitives.h"
#include "rt/reader.h"

namespace rt::disk {

namespace {
struct Disk {
    Plane plane;
    Vec3 centre;
    double radius;
    double radius_squared;
};
}  // namespace

ShapeData read(SceneReader& reader) {
    const Vec3 centre = reader.vec3("disk centre");
    const Vec3 n = normalized(reader.nonzero_vec3("disk normal"));
    const double radius = reader.positive("disk radius");
    return std::make_shared<const Disk>(
        Disk{{n, dot(n, centre)}, centre, radius, radius * radius});
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    const auto& d = *static_cast<const Disk*>(shape);
    const auto t = d.plane.distance(ray, range);
    if (!t || length_squared(ray.at(*t) - d.centre) > d.radius_squared) return false;
    hit = {*t, 0};
    return true;
}

Vec3 normal(const void* shape, const Vec3&, const Hit&) {
    return static_cast<const Disk*>(shape)->plane.normal;
}

Bounds bounds(const void* shape) {
    const auto& d = *static_cast<const Disk*>(shape);
    return disk_bounds(d.centre, d.plane.normal, d.radius);
}

}  // namespace rt::disk
