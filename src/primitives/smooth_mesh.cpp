// Smooth mesh (ID 16): nv; nt; nv vertices, each a position then a normal; nt triangles, each
// three zero-based vertex indices; one surface for the whole. As the mesh (14) for everything
// a ray meets: the same core (mesh_core.h), the same face normals, which decide the side a ray
// is on. Shading uses the blend of the vertex normals instead: at a point with barycentric
// weights (w0, w1, w2), normalise(w0 n0 + w1 n1 + w2 n2).
//
// The weights are computed again from the hit point rather than carried in Hit, which stays
// as small as it is for every other primitive; the point lies in the triangle's plane up to
// rounding, and the weights are clamped to the triangle.
#include <algorithm>
#include <cmath>
#include <string>

#include "primitives/mesh_core.h"
#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::smooth_mesh {

namespace {

// A shading normal closer than this (in each component) to the face normal is the face
// normal itself, so that a triangle whose vertex normals are its face normal shades exactly
// as the flat mesh (14) does, bit for bit.
constexpr double kFlatTolerance = 1e-12;

struct SmoothMesh {
    mesh_core::Core core;
    std::vector<Vec3> normals;  // one per vertex, as written (non-zero, not necessarily unit)
};

ShapeData read(SceneReader& reader) {
    const long vertex_count = reader.whole("smooth mesh vertex count", 3, mesh_core::kMaxCount);
    const Location count_at = reader.next_location();
    const long triangle_count = reader.whole("smooth mesh triangle count", 1, mesh_core::kMaxCount);

    SmoothMesh mesh;
    const auto reserve = static_cast<std::size_t>(std::min(vertex_count, mesh_core::kMaxReserve));
    mesh.core.vertices.reserve(reserve);
    mesh.normals.reserve(reserve);
    for (long i = 0; i < vertex_count; ++i) {
        mesh.core.vertices.push_back(mesh_core::read_vertex(reader, "smooth mesh vertex ", i));
        // A zero normal is refused at its first number; a normal's squared length must be a
        // normal double, so that blends of three cannot overflow.
        mesh.normals.push_back(
            reader.nonzero_vec3(mesh_core::Label("smooth mesh vertex ", i, " normal")));
    }
    mesh.core.vertices.shrink_to_fit();
    mesh.normals.shrink_to_fit();

    const std::size_t skipped =
        mesh_core::build(mesh.core, triangle_count, reader.threads(), [&](long i) {
            std::array<std::uint32_t, 3> index{};
            for (std::uint32_t& k : index)
                k = mesh_core::read_index(reader, "smooth mesh triangle ", i, vertex_count);
            return index;
        });
    if (mesh.core.triangles.empty())
        reader.fail(count_at, "smooth mesh has no triangle with non-zero area (all " +
                                  std::to_string(triangle_count) + " are degenerate)");
    reader.count_skipped_triangles(skipped);
    return std::make_shared<const SmoothMesh>(std::move(mesh));
}

const mesh_core::Core& core(const void* shape) {
    return static_cast<const SmoothMesh*>(shape)->core;
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    return mesh_core::closest(core(shape), ray, range, hit);
}

bool intersect_any(const void* shape, const Ray& ray, Interval range, Hit&) {
    return mesh_core::any(core(shape), ray, range);
}

Vec3 normal(const void* shape, const Vec3&, const Hit& hit) {
    return mesh_core::face(core(shape), hit);
}

// The blend of the vertex normals at the point, turned to the face normal's side (vertex
// normals written against the winding still shade the side a ray sees). Where the blend is
// zero, or within kFlatTolerance of the face normal, it is the face normal.
Vec3 shading_normal(const void* shape, const Vec3& point, const Hit& hit) {
    const auto& m = *static_cast<const SmoothMesh*>(shape);
    const mesh_core::Triangle& tri = m.core.triangle(hit);
    const Vec3 face = mesh_core::face(m.core, hit);
    const Vec3& a = m.core.vertex(tri, 0);
    const Vec3& b = m.core.vertex(tri, 1);
    const Vec3& c = m.core.vertex(tri, 2);
    // Barycentric weights as ratios of areas, on differences scaled to a largest component of
    // about 1 so that no product overflows.
    const double scale = std::max(max_abs_component(b - a), max_abs_component(c - a));
    const Vec3 ab = (b - a) / scale, ac = (c - a) / scale, ap = (point - a) / scale;
    const Vec3 n = cross(ab, ac);
    const double area = dot(n, n);
    double wb = dot(cross(ap, ac), n) / area;
    double wc = dot(cross(ab, ap), n) / area;
    double wa = 1 - wb - wc;
    wa = std::max(wa, 0.0);
    wb = std::max(wb, 0.0);
    wc = std::max(wc, 0.0);
    const Vec3 blend = wa * m.normals[tri.vertex[0]] + wb * m.normals[tri.vertex[1]] +
                       wc * m.normals[tri.vertex[2]];
    const double size = length(blend);
    if (!(size > 0) || !std::isfinite(size)) return face;
    Vec3 s = blend / size;
    if (dot(s, face) < 0) s = -s;
    if (max_abs_component(s - face) <= kFlatTolerance) return face;
    return s;
}

Bounds bounds(const void* shape) { return core(shape).box; }

}  // namespace

// A shadow ray stops at the first triangle it meets.
extern const PrimitiveFunctions functions{.read = read,
                                          .intersect = intersect,
                                          .normal = normal,
                                          .bounds = bounds,
                                          .intersect_any = intersect_any,
                                          .shading_normal = shading_normal};

}  // namespace rt::smooth_mesh
