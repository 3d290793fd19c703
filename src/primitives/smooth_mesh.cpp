// Smooth mesh (ID 16): nv; nt; nv vertices, each a position then a normal; nt triangles, each
// three zero-based vertex indices; one surface for the whole. As the mesh (14) for everything
// a ray meets: the same core (mesh_core.h), the same face normals, which decide the side a ray
// is on. Shading uses the blend of the vertex normals instead: at a point with barycentric
// weights (w0, w1, w2), normalise(w0 n0 + w1 n1 + w2 n2).
//
// The blend is the mesh core's (mesh_core::blended_normal), shared with the mesh from a file
// (15).
#include <algorithm>
#include <string>

#include "primitives/mesh_core.h"
#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::smooth_mesh {

namespace {

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

Vec3 shading_normal(const void* shape, const Vec3& point, const Hit& hit) {
    const auto& m = *static_cast<const SmoothMesh*>(shape);
    return mesh_core::blended_normal(m.core, m.normals, point, hit);
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
