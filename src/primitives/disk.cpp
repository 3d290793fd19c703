// Disk (ID 3): centre; normal; radius. The plane through the centre, kept within the radius
// (section 2.4 of the original).
#include "primitives/planar.h"
#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::disk {

namespace {

ShapeData read(SceneReader& reader) {
    const Vec3 centre = reader.vec3("disk centre");
    const Vec3 n = reader.direction("disk normal");
    const double radius = reader.positive("disk radius");
    return reader.shape_data(Ring::make(centre, n, radius, 0));
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    return static_cast<const Ring*>(shape)->intersect(ray, range, hit);
}

Vec3 normal(const void* shape, const Vec3&, const Hit&) {
    return static_cast<const Ring*>(shape)->plane.normal;
}

Bounds bounds(const void* shape) { return static_cast<const Ring*>(shape)->bounds(); }

}  // namespace

extern const PrimitiveFunctions functions{
    .read = read, .intersect = intersect, .normal = normal, .bounds = bounds};

}  // namespace rt::disk
