// What the meshes (14, and 16 with vertex normals) share: compact triangles in the leaf order
// of their own hierarchy, the watertight test (watertight.h), zero-area triangles skipped, and
// the labels and index reader their messages use.
//
// Storage: the vertices once, then per triangle three 32-bit indices and its place in the
// file (16 bytes) and its packed copy for the leaf test (80 bytes), plus the hierarchy's
// nodes (32 bytes per binary node and 128 per wide node, one per at most a few triangles).
#pragma once

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "accel/bvh.h"
#include "accel/parallel.h"
#include "primitives/watertight.h"
#include "rt/primitive.h"

namespace rt {
class SceneReader;
}

namespace rt::mesh_core {

// The most vertices and triangles a mesh may have: Hit::part, an int, names a triangle.
inline constexpr long kMaxCount = 2'147'483'647;
// Storage is reserved for at most this many vertices and triangles up front, and grows as
// they are read beyond it: the counts alone never decide how much is allocated.
inline constexpr long kMaxReserve = 1L << 16;
// The largest vertex coordinate, in absolute value. Below it, the products of the
// intersection test (of differences of coordinates, up to the third power) cannot overflow
// a double, even for rays from as far as this.
inline constexpr double kMaxCoordinate = 1e100;

struct Triangle {
    // The vertices in lexicographic order of their positions (SortedTriangle), so that the
    // edge functions of a shared edge are computed alike from both sides.
    std::array<std::uint32_t, 3> vertex;
    // The triangle's place among the file's triangles, times two, plus one when the sorted
    // order reverses the written winding.
    std::uint32_t place_and_flip;

    std::uint32_t place() const { return place_and_flip >> 1; }
    bool flipped() const { return (place_and_flip & 1) != 0; }
};
static_assert(sizeof(Triangle) == 16);

// A triangle as the hierarchy's leaves test it: its vertices' positions in sorted order,
// copied out of the vertex list so that a leaf's triangles lie side by side in memory and
// are tested without an index, and its place among the file's triangles for ties. The hit
// triangle's face normal is computed from it too (it was just tested, so it is in cache),
// hence the winding bit, which fills what would be padding.
struct PackedTriangle {
    Vec3 vertex[3];
    std::uint32_t place;
    std::uint32_t flipped;  // 1 when the sorted order reverses the written winding
};
static_assert(sizeof(PackedTriangle) == 80);

// Triangles as a mesh holds them, and as its build gathers them.
using Triangles = std::vector<Triangle, UninitializedAllocator<Triangle>>;

struct Core {
    std::vector<Vec3, UninitializedAllocator<Vec3>> vertices;
    // In the hierarchy's leaf order (Hit::part indexes it), and packed, in the same order.
    // Large arrays: in 2 MiB pages where the kernel offers them (rt/large_pages.h).
    Triangles triangles;
    std::vector<PackedTriangle, UninitializedAllocator<PackedTriangle>> packed;
    Bvh bvh;
    Bounds box;

    const Vec3& vertex(const Triangle& t, std::size_t k) const { return vertices[t.vertex[k]]; }
    const Triangle& triangle(const Hit& hit) const {
        return triangles[static_cast<std::size_t>(hit.part)];
    }
};

// A field's name with a number in it ("mesh vertex 7"), built without allocating: a mesh
// names millions of fields and almost never needs the name.
class Label {
  public:
    Label(std::string_view before, long number, std::string_view after = {}) {
        append(before);
        size_ = static_cast<std::size_t>(
            std::to_chars(text_ + size_, text_ + sizeof text_, number).ptr - text_);
        append(after);
    }
    operator std::string_view() const { return {text_, size_}; }
    std::string str() const { return {text_, size_}; }

  private:
    void append(std::string_view s) {
        const std::size_t n = std::min(s.size(), sizeof text_ - size_);
        std::copy_n(s.data(), n, text_ + size_);
        size_ += n;
    }
    char text_[96];  // the names above with any long, and room to spare
    std::size_t size_ = 0;
};

// Reads one vertex position ("<name> vertex i"), checked against kMaxCoordinate.
Vec3 read_vertex(SceneReader& reader, std::string_view name, long i);
// Reads one vertex index of triangle `triangle` ("<name> triangle i vertex index"), a whole
// number in [0, vertex_count).
std::uint32_t read_index(SceneReader& reader, std::string_view name, long triangle,
                         long vertex_count);

// Collects the triangles of `core.vertices`, which must be filled: next(i) gives the three
// written indices of triangle i (each below the vertex count). Zero-area triangles are
// skipped; the rest are sorted (watertight.h), boxed, put in a hierarchy built on `threads`
// threads and stored in its leaf order. Returns how many were skipped.
template <class Next>
std::size_t build(Core& core, long triangle_count, int threads, Next&& next);

// The nearest triangle hit in range; of triangles at the same distance, the one written first.
// `prepared`, where given, is WideRay(ray, range.t_min), usable (Bvh::closest_leaves).
bool closest(const Core& core, const Ray& ray, Interval range, Hit& hit,
             const WideRay* prepared = nullptr);
// Whether any triangle lies along the ray in range.
bool any(const Core& core, const Ray& ray, Interval range, const WideRay* prepared = nullptr);
// The hit triangle's outward normal, (v1 - v0) x (v2 - v0) normalised in the written winding.
Vec3 face(const Core& core, const Hit& hit);

// The shading normal of a mesh with vertex normals (one per vertex) at a point of the hit
// triangle: the barycentric blend of its corners' normals, normalised and turned to the face
// normal's side (vertex normals written against the winding still shade the side a ray
// sees). Where the blend is zero, where a corner's normal is zero, or within 1e-12 of the
// face normal, it is the face normal. face_n: face(core, hit).
Vec3 blended_normal(const Core& core, std::span<const Vec3> normals, const Vec3& point,
                    const Hit& hit, const Vec3& face_n);

// A mesh with vertex normals for shading (16, and 15 where it is smooth): one normal per vertex,
// or none (flat: the shading normal is the face normal).
struct ShadedMesh {
    Core core;
    std::vector<Vec3> normals;
};

// The table functions of a ShadedMesh, which the smooth mesh (16) and the mesh from a file (15)
// both use beside their own read function. A shadow ray stops at the first triangle it meets.
namespace shaded {
bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit);
bool intersect_any(const void* shape, const Ray& ray, Interval range, Hit& hit);
bool intersect_prepared(const void* shape, const Ray& ray, Interval range, Hit& hit,
                        const WideRay* prepared);
bool intersect_any_prepared(const void* shape, const Ray& ray, Interval range, Hit& hit,
                            const WideRay* prepared);
Vec3 normal(const void* shape, const Vec3& point, const Hit& hit);
Vec3 shading_normal(const void* shape, const Vec3& point, const Hit& hit, const Vec3& face_n);
Bounds bounds(const void* shape);
std::vector<Bounds> outline(const void* shape, std::size_t at_most);
}  // namespace shaded

// The many_parts column of every mesh, true for each: a test searches its triangles, through
// the mesh's own hierarchy.
inline bool always_true(const void*) { return true; }

namespace shaded {
// The table row of a ShadedMesh read by `read` (15 and 16): everything but reading is the
// shaded mesh's.
constexpr PrimitiveFunctions functions_with(ReadShapeFn* read) {
    return {.read = read,
            .intersect = intersect,
            .normal = normal,
            .bounds = bounds,
            .intersect_any = intersect_any,
            .shading_normal = shading_normal,
            .many_parts = always_true,
            .outline = outline,
            .intersect_prepared = intersect_prepared,
            .intersect_any_prepared = intersect_any_prepared};
}
}  // namespace shaded
// The outline column of the mesh (14), whose shape is a Core: its hierarchy's.
inline std::vector<Bounds> core_outline(const void* shape, std::size_t at_most) {
    return static_cast<const Core*>(shape)->bvh.outline(at_most);
}

// Out of line: the part of build that does not depend on where the indices come from.
void finish(Core& core, Triangles& triangles, int threads);

template <class Next>
std::size_t build(Core& core, long triangle_count, int threads, Next&& next) {
    Triangles triangles;
    triangles.reserve(static_cast<std::size_t>(std::min(triangle_count, kMaxReserve)));
    std::size_t skipped = 0;
    for (long i = 0; i < triangle_count; ++i) {
        const std::array<std::uint32_t, 3> index = next(i);
        const Vec3& v0 = core.vertices[index[0]];
        const Vec3& v1 = core.vertices[index[1]];
        const Vec3& v2 = core.vertices[index[2]];
        // Zero area: no normal in double precision, so nothing for a ray to hit.
        if (face_normal(v0, v1, v2) == Vec3{}) {
            ++skipped;
            continue;
        }
        const SortedTriangle s = SortedTriangle::sort(v0, v1, v2);
        Triangle t{};
        for (std::size_t k = 0; k < 3; ++k)
            t.vertex[k] = index[static_cast<std::size_t>(s.order[k])];
        t.place_and_flip = static_cast<std::uint32_t>(i) << 1 | (s.flipped ? 1 : 0);
        triangles.push_back(t);
        for (const Vec3* v : {&v0, &v1, &v2}) core.box.expand(*v);
    }
    finish(core, triangles, threads);
    return skipped;
}

}  // namespace rt::mesh_core
