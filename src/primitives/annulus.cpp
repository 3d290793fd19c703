// Annulus (ID 4): centre; normal; outer radius; inner radius. A disk with a hole
// (section 2.4 of the original).
#include "primitives/planar.h"
#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::annulus {

namespace {

ShapeData read(SceneReader& reader) {
    const Vec3 centre = reader.vec3("annulus centre");
    const Vec3 n = reader.direction("annulus normal");
    const double outer = reader.positive("annulus outer radius");
    const Location inner_at = reader.next_location();
    const double inner = reader.non_negative("annulus inner radius");
    if (!(inner < outer))
        reader.fail(inner_at, "annulus inner radius must be less than the outer radius " +
                                  format_number(outer) + ", got " + format_number(inner));
    return reader.shape_data(Ring::make(centre, n, outer, inner));
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

}  // namespace rt::annulus
