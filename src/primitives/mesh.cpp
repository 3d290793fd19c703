// Mesh (ID 14): nv; nt; nv vertices; nt triangles, each three zero-based vertex indices; one
// surface for the whole. A triangle's outward normal is (v1 - v0) x (v2 - v0), normalised.
// Zero-area triangles are skipped (and counted for `rt -r`); an index outside [0, nv) is an
// error. A mesh encloses no volume as far as rt knows: it has no inside.
//
// The storage, the hierarchy and the watertight test are the mesh core's (mesh_core.h),
// shared with the smooth mesh (16).
#include <algorithm>
#include <string>

#include "primitives/mesh_core.h"
#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::mesh {

namespace {

using mesh_core::Core;

ShapeData read(SceneReader& reader) {
    const long vertex_count = reader.whole("mesh vertex count", 3, mesh_core::kMaxCount);
    const Location count_at = reader.next_location();
    const long triangle_count = reader.whole("mesh triangle count", 1, mesh_core::kMaxCount);

    Core mesh;
    mesh.vertices.reserve(static_cast<std::size_t>(std::min(vertex_count, mesh_core::kMaxReserve)));
    for (long i = 0; i < vertex_count; ++i)
        mesh.vertices.push_back(mesh_core::read_vertex(reader, "mesh vertex ", i));
    mesh.vertices.shrink_to_fit();

    const std::size_t skipped =
        mesh_core::build(mesh, triangle_count, reader.threads(), [&](long i) {
            std::array<std::uint32_t, 3> index{};
            for (std::uint32_t& k : index)
                k = mesh_core::read_index(reader, "mesh triangle ", i, vertex_count);
            return index;
        });
    if (mesh.triangles.empty())
        reader.fail(count_at, "mesh has no triangle with non-zero area (all " +
                                  std::to_string(triangle_count) + " are degenerate)");
    reader.count_mesh_triangles(mesh.triangles.size(), skipped);
    return std::make_shared<const Core>(std::move(mesh));
}

bool intersect_prepared(const void* shape, const Ray& ray, Interval range, Hit& hit,
                        const WideRay* prepared) {
    return mesh_core::closest(*static_cast<const Core*>(shape), ray, range, hit, prepared);
}

bool intersect_any_prepared(const void* shape, const Ray& ray, Interval range, Hit&,
                            const WideRay* prepared) {
    return mesh_core::any(*static_cast<const Core*>(shape), ray, range, prepared);
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    return intersect_prepared(shape, ray, range, hit, nullptr);
}

bool intersect_any(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    return intersect_any_prepared(shape, ray, range, hit, nullptr);
}

Vec3 normal(const void* shape, const Vec3&, const Hit& hit) {
    return mesh_core::face(*static_cast<const Core*>(shape), hit);
}

Bounds bounds(const void* shape) { return static_cast<const Core*>(shape)->box; }

}  // namespace

// A shadow ray stops at the first triangle it meets.
extern const PrimitiveFunctions functions{.read = read,
                                          .intersect = intersect,
                                          .normal = normal,
                                          .bounds = bounds,
                                          .intersect_any = intersect_any,
                                          .many_parts = mesh_core::always_true,
                                          .outline = mesh_core::core_outline,
                                          .intersect_prepared = intersect_prepared,
                                          .intersect_any_prepared = intersect_any_prepared};

}  // namespace rt::mesh
