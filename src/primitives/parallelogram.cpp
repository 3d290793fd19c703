// Parallelogram (ID 6): vertex v; edge a; edge b. Points v + alpha a + beta b with
// 0 <= alpha, beta <= 1 (section 2.6 of the original).
#include "primitives/planar.h"
#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::parallelogram {

namespace {

ShapeData read(SceneReader& reader) {
    const Location at = reader.next_location();
    const Vec3 v = reader.vec3("parallelogram vertex");
    const Vec3 a = reader.vec3("parallelogram edge a");
    const Vec3 b = reader.vec3("parallelogram edge b");
    Bounds box;
    for (const Vec3& corner : {v, v + a, v + b, v + a + b}) box.expand(corner);
    const auto patch = EdgePatch::make(v, a, b, box);
    if (!patch) reader.fail(at, "parallelogram has zero area (its edges are parallel or zero)");
    return reader.shape_data(*patch);
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    const auto p = static_cast<const EdgePatch*>(shape)->locate(ray, range);
    if (!p || p->alpha < 0 || p->beta < 0 || p->alpha > 1 || p->beta > 1) return false;
    hit = {p->t, 0};
    return true;
}

Vec3 normal(const void* shape, const Vec3&, const Hit&) {
    return static_cast<const EdgePatch*>(shape)->plane.normal;
}

Bounds bounds(const void* shape) { return static_cast<const EdgePatch*>(shape)->box; }

}  // namespace

extern const PrimitiveFunctions functions{
    .read = read, .intersect = intersect, .normal = normal, .bounds = bounds};

}  // namespace rt::parallelogram
