// Triangle (ID 5): three vertices. Points v0 + alpha a + beta b with alpha, beta >= 0 and
// alpha + beta <= 1, where a = v1 - v0 and b = v2 - v0 (section 2.5 of the original).
#include "primitives/planar.h"
#include "primitives/primitives.h"
#include "rt/reader.h"

namespace rt::triangle {

ShapeData read(SceneReader& reader) {
    const Location at = reader.next_location();
    const Vec3 v0 = reader.vec3("triangle vertex 0");
    const Vec3 v1 = reader.vec3("triangle vertex 1");
    const Vec3 v2 = reader.vec3("triangle vertex 2");
    Bounds box;
    for (const Vec3& v : {v0, v1, v2}) box.expand(v);
    const auto patch = EdgePatch::make(v0, v1 - v0, v2 - v0, box);
    if (!patch) reader.fail(at, "triangle has zero area (its vertices are collinear)");
    return std::make_shared<const EdgePatch>(*patch);
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    const auto p = static_cast<const EdgePatch*>(shape)->locate(ray, range);
    if (!p || p->alpha < 0 || p->beta < 0 || p->alpha + p->beta > 1) return false;
    hit = {p->t, 0};
    return true;
}

Vec3 normal(const void* shape, const Vec3&, const Hit&) {
    return static_cast<const EdgePatch*>(shape)->plane.normal;
}

Bounds bounds(const void* shape) { return static_cast<const EdgePatch*>(shape)->box; }

}  // namespace rt::triangle
