// Plane (ID 2): D; normal n. The points with n.x = D (section 2.3 of the original). Its inside,
// for CSG, is the half-space n.x < D.
#include <cmath>

#include "primitives/planar.h"
#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::plane {

namespace {

ShapeData read(SceneReader& reader) {
    const double d = reader.number("plane D");
    const Location normal_at = reader.next_location();
    double len = 0;
    const Vec3 n = reader.direction("plane normal", &len);
    // Scaling n and D together leaves the plane unchanged; store it with a unit normal.
    const double distance = d / len;
    if (!std::isfinite(distance))
        reader.fail(normal_at, "plane D divided by the normal's length must be finite");
    return reader.shape_data(Plane{n, distance});
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    const auto t = static_cast<const Plane*>(shape)->distance(ray, range);
    if (!t) return false;
    hit = {*t, 0};
    return true;
}

Vec3 normal(const void* shape, const Vec3&, const Hit&) {
    return static_cast<const Plane*>(shape)->normal;
}

Bounds bounds(const void*) { return Bounds::infinite(); }

bool inside(const void* shape, const Vec3& point) {
    const auto& p = *static_cast<const Plane*>(shape);
    return dot(p.normal, point) < p.offset;
}

}  // namespace

extern const PrimitiveFunctions functions{
    .read = read, .intersect = intersect, .normal = normal, .bounds = bounds, .inside = inside};

}  // namespace rt::plane
