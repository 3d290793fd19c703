#include "primitives/mesh_core.h"

#include <algorithm>
#include <cmath>

#include "rt/reader.h"

namespace rt::mesh_core {

Vec3 read_vertex(SceneReader& reader, std::string_view name, long i) {
    const Location at = reader.next_location();
    // The field's name is made only when a coordinate is not a plain decimal (or is bad).
    Vec3 v;
    for (double* c : {&v.x, &v.y, &v.z})
        if (!reader.plain_number(*c)) *c = reader.number(Label(name, i));
    if (!(max_abs_component(v) <= kMaxCoordinate))
        reader.fail(at, Label(name, i).str() + " coordinates must be at most " +
                            format_number(kMaxCoordinate) + " in absolute value");
    return v;
}

std::uint32_t read_index(SceneReader& reader, std::string_view name, long triangle,
                         long vertex_count) {
    const auto what = [&] { return Label(name, triangle, " vertex index"); };
    double value = 0;
    if (!reader.plain_number(value)) value = reader.number(what());
    const Location at = reader.last_number_location();
    if (value != std::floor(value))
        reader.fail(at, what().str() + " must be a whole number, got " + reader.last_number_text());
    if (value < 0 || value >= static_cast<double>(vertex_count))
        reader.fail(at, what().str() + " must be in [0, " + std::to_string(vertex_count) +
                            "), got " + reader.last_number_text());
    return static_cast<std::uint32_t>(value);
}

void finish(Core& core, Triangles& triangles, int threads) {
    if (triangles.empty()) return;
    // The hierarchy numbers triangles in leaf order; store them in that order. It asks for
    // each triangle's box as it makes its reference: cheaper than storing them (48 bytes a
    // triangle of fresh memory to touch).
    struct Source {
        const Core& core;
        const Triangles& triangles;
    } const source{core, triangles};
    core.bvh = Bvh(triangles.size(),
                   {&source,
                    [](const void* context, std::uint32_t i) {
                        const auto& s = *static_cast<const Source*>(context);
                        const Triangle& t = s.triangles[i];
                        Bounds box;
                        for (std::size_t k = 0; k < 3; ++k) box.expand(s.core.vertex(t, k));
                        return box;
                    }},
                   threads);
    core.bvh.drop_binary_nodes();
    core.triangles.reserve(triangles.size());
    for (const std::uint32_t i : core.bvh.take_order()) core.triangles.push_back(triangles[i]);
    core.packed.reserve(core.triangles.size());
    for (const Triangle& t : core.triangles)
        core.packed.push_back({{core.vertex(t, 0), core.vertex(t, 1), core.vertex(t, 2)},
                               t.place(),
                               t.flipped() ? 1u : 0u});
}

bool closest(const Core& m, const Ray& ray, Interval range, Hit& hit, const WideRay* prepared) {
    const TriangleRay triangle_ray(ray);
    double best = range.t_max;
    constexpr std::uint32_t kNone = ~std::uint32_t{0};
    std::uint32_t best_position = kNone, best_place = 0;
    // Of triangles hit at the same distance, the one written first wins, whatever order the
    // hierarchy visits them in.
    m.bvh.closest_leaves(
        ray, range.t_min, best,
        [&](std::uint32_t first, std::uint32_t count) {
            const PackedTriangle* leaf = m.packed.data() + first;
            for (std::uint32_t i = 0; i < count; ++i) {
                const PackedTriangle& tri = leaf[i];
                double t = 0;
                if (!triangle_ray.crosses(tri.vertex[0], tri.vertex[1], tri.vertex[2], t) ||
                    !(t > range.t_min))
                    continue;
                if (t < best || (t == best && best_position != kNone && tri.place < best_place)) {
                    best = t;
                    best_place = tri.place;
                    best_position = first + i;
                }
            }
        },
        prepared);
    if (best_position == kNone) return false;
    hit = {best, static_cast<int>(best_position)};
    return true;
}

bool any(const Core& m, const Ray& ray, Interval range, const WideRay* prepared) {
    const TriangleRay triangle_ray(ray);
    return m.bvh.any_leaves(
        ray, range.t_min, range.t_max,
        [&](std::uint32_t first, std::uint32_t count) {
            const PackedTriangle* leaf = m.packed.data() + first;
            for (std::uint32_t i = 0; i < count; ++i) {
                double t = 0;
                if (triangle_ray.crosses(leaf[i].vertex[0], leaf[i].vertex[1], leaf[i].vertex[2],
                                         t) &&
                    range.contains(t))
                    return true;
            }
            return false;
        },
        prepared);
}

// From the packed copy, not the vertex list: the same doubles, and already in cache, where
// the vertex list's three would each be a load from anywhere in a large mesh.
Vec3 face(const Core& m, const Hit& hit) {
    const PackedTriangle& tri = m.packed[static_cast<std::size_t>(hit.part)];
    const Vec3 n = face_normal(tri.vertex[0], tri.vertex[1], tri.vertex[2]);
    return tri.flipped != 0 ? -n : n;
}

namespace {
// A shading normal closer than this (in each component) to the face normal is the face
// normal itself, so that a triangle whose vertex normals are its face normal shades exactly
// as the flat mesh (14) does, bit for bit.
constexpr double kFlatTolerance = 1e-12;
}  // namespace

// The weights are computed again from the hit point rather than carried in Hit, which stays
// as small as it is for every other primitive; the point lies in the triangle's plane up to
// rounding, and the weights are clamped to the triangle.
Vec3 blended_normal(const Core& m, std::span<const Vec3> normals, const Vec3& point, const Hit& hit,
                    const Vec3& face_n) {
    const Triangle& tri = m.triangle(hit);
    const Vec3& n0 = normals[tri.vertex[0]];
    const Vec3& n1 = normals[tri.vertex[1]];
    const Vec3& n2 = normals[tri.vertex[2]];
    // A corner without a normal (a file's zero normal) makes the triangle flat.
    const Vec3 none{};
    if (n0 == none || n1 == none || n2 == none) return face_n;
    const PackedTriangle& packed = m.packed[static_cast<std::size_t>(hit.part)];
    const Vec3& a = packed.vertex[0];
    const Vec3& b = packed.vertex[1];
    const Vec3& c = packed.vertex[2];
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
    const Vec3 blend = wa * n0 + wb * n1 + wc * n2;
    const double size = length(blend);
    if (!(size > 0) || !std::isfinite(size)) return face_n;
    Vec3 s = blend / size;
    if (dot(s, face_n) < 0) s = -s;
    if (max_abs_component(s - face_n) <= kFlatTolerance) return face_n;
    return s;
}

namespace shaded {

namespace {
const ShadedMesh& mesh_of(const void* shape) { return *static_cast<const ShadedMesh*>(shape); }
}  // namespace

bool intersect_prepared(const void* shape, const Ray& ray, Interval range, Hit& hit,
                        const WideRay* prepared) {
    return closest(mesh_of(shape).core, ray, range, hit, prepared);
}

bool intersect_any_prepared(const void* shape, const Ray& ray, Interval range, Hit&,
                            const WideRay* prepared) {
    return any(mesh_of(shape).core, ray, range, prepared);
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    return intersect_prepared(shape, ray, range, hit, nullptr);
}

bool intersect_any(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    return intersect_any_prepared(shape, ray, range, hit, nullptr);
}

Vec3 normal(const void* shape, const Vec3&, const Hit& hit) {
    return face(mesh_of(shape).core, hit);
}

// face_n: normal()'s, the face normal, which the blend would otherwise compute again (a
// square root and four divisions).
Vec3 shading_normal(const void* shape, const Vec3& point, const Hit& hit, const Vec3& face_n) {
    const ShadedMesh& m = mesh_of(shape);
    if (m.normals.empty()) return face_n;
    return blended_normal(m.core, m.normals, point, hit, face_n);
}

Bounds bounds(const void* shape) { return mesh_of(shape).core.box; }

std::vector<Bounds> outline(const void* shape, std::size_t at_most) {
    return mesh_of(shape).core.bvh.outline(at_most);
}

}  // namespace shaded

}  // namespace rt::mesh_core
