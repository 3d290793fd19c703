// Smooth mesh (ID 16): nv; nt; nv vertices, each a position then a normal; nt triangles, each
// three zero-based vertex indices; one surface for the whole. As the mesh (14) for everything
// a ray meets: the same core (mesh_core.h), the same face normals, which decide the side a ray
// is on. Shading uses the blend of the vertex normals instead: at a point with barycentric
// weights (w0, w1, w2), normalise(w0 n0 + w1 n1 + w2 n2).
//
// The shape and every function but read are the mesh core's shaded mesh
// (mesh_core::ShadedMesh), shared with the mesh from a file (15).
#include <algorithm>
#include <string>

#include "primitives/mesh_core.h"
#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::smooth_mesh {

namespace {

ShapeData read(SceneReader& reader) {
    const long vertex_count = reader.whole("smooth mesh vertex count", 3, mesh_core::kMaxCount);
    const Location count_at = reader.next_location();
    const long triangle_count = reader.whole("smooth mesh triangle count", 1, mesh_core::kMaxCount);

    // The normals as written: non-zero, not necessarily unit.
    mesh_core::ShadedMesh mesh;
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
    reader.count_mesh_triangles(mesh.core.triangles.size(), skipped);
    return std::make_shared<const mesh_core::ShadedMesh>(std::move(mesh));
}

}  // namespace

// Everything but reading is the shaded mesh's (mesh_core.h), shared with the mesh from a file.
extern const PrimitiveFunctions functions = mesh_core::shaded::functions_with(read);

}  // namespace rt::smooth_mesh
