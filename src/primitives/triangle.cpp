// Triangle (ID 5): three vertices. Points v0 + alpha a + beta b with alpha, beta >= 0 and
// alpha + beta <= 1, where a = v1 - v0 and b = v2 - v0 (section 2.5 of the original). Rays
// meet it by the watertight test that the mesh uses too, so triangles written one by one
// that share an edge (the same two vertices, to the last bit) leave no gap along it, and a
// mesh and the same triangles written separately are hit at the same distances.
#include "primitives/planar.h"
#include "primitives/watertight.h"
#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::triangle {

namespace {

struct Triangle {
    std::array<Vec3, 3> sorted;  // the vertices in lexicographic order, for TriangleRay
    Vec3 normal;                 // unit, along (v1 - v0) x (v2 - v0) as written
    Bounds box;
};

ShapeData read(SceneReader& reader) {
    const Location at = reader.next_location();
    const std::array<Vec3, 3> v{reader.vec3("triangle vertex 0"), reader.vec3("triangle vertex 1"),
                                reader.vec3("triangle vertex 2")};
    // Zero area as for the parallelogram: edges parallel to within rounding.
    if (!EdgeFrame::make(v[0], v[1] - v[0], v[2] - v[0]))
        reader.fail(at, "triangle has zero area (its vertices are collinear)");
    const SortedTriangle s = SortedTriangle::sort(v[0], v[1], v[2]);
    Triangle t;
    for (std::size_t k = 0; k < 3; ++k) {
        t.sorted[k] = v[static_cast<std::size_t>(s.order[k])];
        t.box.expand(v[k]);
    }
    // From the sorted vertices, as the mesh computes it.
    t.normal = face_normal(t.sorted[0], t.sorted[1], t.sorted[2]);
    if (s.flipped) t.normal = -t.normal;
    return reader.shape_data(t);
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    const auto& tri = *static_cast<const Triangle*>(shape);
    double t = 0;
    if (!TriangleRay(ray).crosses(tri.sorted[0], tri.sorted[1], tri.sorted[2], t) ||
        !range.contains(t))
        return false;
    hit = {t, 0};
    return true;
}

Vec3 normal(const void* shape, const Vec3&, const Hit&) {
    return static_cast<const Triangle*>(shape)->normal;
}

Bounds bounds(const void* shape) { return static_cast<const Triangle*>(shape)->box; }

std::vector<Vec3> corners(const void* shape) {
    const auto& t = *static_cast<const Triangle*>(shape);
    return {t.sorted.begin(), t.sorted.end()};
}

}  // namespace

extern const PrimitiveFunctions functions{
    .read = read, .intersect = intersect, .normal = normal, .bounds = bounds, .corners = corners};

}  // namespace rt::triangle
