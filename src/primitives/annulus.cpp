// Annulus (ID 4): centre; normal; outer radius; inner radius. A disk with a hole
// (section 2.4 of the original).
#include "primitives/planar.h"
#include "primitives/primitives.h"
#include "rt/reader.h"

namespace rt::annulus {

namespace {
struct Annulus {
    Plane plane;
    Vec3 centre;
    double outer;
    double outer_squared;
    double inner_squared;
};
}  // namespace

ShapeData read(SceneReader& reader) {
    const Vec3 centre = reader.vec3("annulus centre");
    const Vec3 n = normalized(reader.nonzero_vec3("annulus normal"));
    const double outer = reader.positive("annulus outer radius");
    const Location inner_at = reader.next_location();
    const double inner = reader.non_negative("annulus inner radius");
    if (!(inner < outer))
        reader.fail(inner_at, "annulus inner radius must be less than the outer radius " +
                                  format_number(outer) + ", got " + format_number(inner));
    return std::make_shared<const Annulus>(
        Annulus{{n, dot(n, centre)}, centre, outer, outer * outer, inner * inner});
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    const auto& a = *static_cast<const Annulus*>(shape);
    const auto t = a.plane.distance(ray, range);
    if (!t) return false;
    const double r2 = length_squared(ray.at(*t) - a.centre);
    if (r2 > a.outer_squared || r2 < a.inner_squared) return false;
    hit = {*t, 0};
    return true;
}

Vec3 normal(const void* shape, const Vec3&, const Hit&) {
    return static_cast<const Annulus*>(shape)->plane.normal;
}

Bounds bounds(const void* shape) {
    const auto& a = *static_cast<const Annulus*>(shape);
    return disk_bounds(a.centre, a.plane.normal, a.outer);
}

}  // namespace rt::annulus
