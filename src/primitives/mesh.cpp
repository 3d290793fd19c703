// Mesh (ID 14): nv; nt; nv vertices; nt triangles, each three zero-based vertex indices; one
// surface for the whole. A triangle's outward normal is (v1 - v0) x (v2 - v0), normalised.
// Zero-area triangles are skipped (and counted for `rt -r`); an index outside [0, nv) is an
// error. A mesh encloses no volume as far as rt knows: it has no inside.
//
// Storage is compact: the vertices once, then per triangle three 32-bit indices and its place
// in the file (16 bytes), in the order the leaves of the mesh's own hierarchy hold them. Rays
// meet triangles by the watertight test (watertight.h), so none slips through a shared edge.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "accel/bvh.h"
#include "primitives/watertight.h"
#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::mesh {

namespace {

// The most vertices and triangles a mesh may have: Hit::part, an int, names a triangle.
constexpr long kMaxCount = 2'147'483'647;
// Storage is reserved for at most this many vertices and triangles up front, and grows as
// they are read beyond it: the counts alone never decide how much is allocated.
constexpr long kMaxReserve = 1L << 16;
// The largest vertex coordinate, in absolute value. Below it, the products of the
// intersection test (of differences of coordinates, up to the third power) cannot overflow
// a double, even for rays from as far as this.
constexpr double kMaxCoordinate = 1e100;

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

struct Mesh {
    std::vector<Vec3> vertices;
    std::vector<Triangle> triangles;  // in the hierarchy's leaf order; Hit::part indexes it
    Bvh bvh;
    Bounds box;

    const Vec3& vertex(const Triangle& t, std::size_t k) const { return vertices[t.vertex[k]]; }
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

std::uint32_t read_index(SceneReader& reader, long triangle, long vertex_count) {
    const Location at = reader.next_location();
    const Label what("mesh triangle ", triangle, " vertex index");
    const double value = reader.number(what);
    if (value != std::floor(value))
        reader.fail(at, what.str() + " must be a whole number, got " + reader.last_number_text());
    if (value < 0 || value >= static_cast<double>(vertex_count))
        reader.fail(at, what.str() + " must be in [0, " + std::to_string(vertex_count) + "), got " +
                            reader.last_number_text());
    return static_cast<std::uint32_t>(value);
}

ShapeData read(SceneReader& reader) {
    const long vertex_count = reader.whole("mesh vertex count", 3, kMaxCount);
    const Location count_at = reader.next_location();
    const long triangle_count = reader.whole("mesh triangle count", 1, kMaxCount);

    Mesh mesh;
    mesh.vertices.reserve(static_cast<std::size_t>(std::min(vertex_count, kMaxReserve)));
    for (long i = 0; i < vertex_count; ++i) {
        const Location at = reader.next_location();
        const Label what("mesh vertex ", i);
        const Vec3 v = reader.vec3(what);
        if (!(max_abs_component(v) <= kMaxCoordinate))
            reader.fail(at, what.str() + " coordinates must be at most " +
                                format_number(kMaxCoordinate) + " in absolute value");
        mesh.vertices.push_back(v);
    }
    mesh.vertices.shrink_to_fit();

    std::vector<Triangle> triangles;
    std::vector<Bounds> boxes;
    triangles.reserve(static_cast<std::size_t>(std::min(triangle_count, kMaxReserve)));
    boxes.reserve(triangles.capacity());
    std::size_t skipped = 0;
    for (long i = 0; i < triangle_count; ++i) {
        std::array<std::uint32_t, 3> index{};
        for (std::uint32_t& k : index) k = read_index(reader, i, vertex_count);
        const Vec3& v0 = mesh.vertices[index[0]];
        const Vec3& v1 = mesh.vertices[index[1]];
        const Vec3& v2 = mesh.vertices[index[2]];
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
        Bounds box;
        for (const Vec3* v : {&v0, &v1, &v2}) box.expand(*v);
        boxes.push_back(box);
        mesh.box.expand(box.min);
        mesh.box.expand(box.max);
    }
    if (triangles.empty())
        reader.fail(count_at, "mesh has no triangle with non-zero area (all " +
                                  std::to_string(triangle_count) + " are degenerate)");
    reader.count_skipped_triangles(skipped);

    // The hierarchy numbers triangles in leaf order; store them in that order.
    mesh.bvh = Bvh(boxes, reader.threads());
    boxes = {};
    mesh.triangles.reserve(triangles.size());
    for (const std::uint32_t i : mesh.bvh.take_order()) mesh.triangles.push_back(triangles[i]);
    return std::make_shared<const Mesh>(std::move(mesh));
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    const auto& m = *static_cast<const Mesh*>(shape);
    const TriangleRay triangle_ray(ray);
    double best = range.t_max;
    const Triangle* best_triangle = nullptr;
    std::uint32_t best_position = 0;
    // Of triangles hit at the same distance, the one written first wins, whatever order the
    // hierarchy visits them in.
    m.bvh.closest(ray, range.t_min, best, [&](std::uint32_t position) {
        const Triangle& tri = m.triangles[position];
        double t = 0;
        if (!triangle_ray.crosses(m.vertex(tri, 0), m.vertex(tri, 1), m.vertex(tri, 2), t) ||
            !(t > range.t_min))
            return;
        if (t < best ||
            (t == best && best_triangle != nullptr && tri.place() < best_triangle->place())) {
            best = t;
            best_triangle = &tri;
            best_position = position;
        }
    });
    if (best_triangle == nullptr) return false;
    hit = {best, static_cast<int>(best_position)};
    return true;
}

bool intersect_any(const void* shape, const Ray& ray, Interval range, Hit&) {
    const auto& m = *static_cast<const Mesh*>(shape);
    const TriangleRay triangle_ray(ray);
    return m.bvh.any(ray, range.t_min, range.t_max, [&](std::uint32_t position) {
        const Triangle& tri = m.triangles[position];
        double t = 0;
        return triangle_ray.crosses(m.vertex(tri, 0), m.vertex(tri, 1), m.vertex(tri, 2), t) &&
               range.contains(t);
    });
}

Vec3 normal(const void* shape, const Vec3&, const Hit& hit) {
    const auto& m = *static_cast<const Mesh*>(shape);
    const Triangle& tri = m.triangles[static_cast<std::size_t>(hit.part)];
    const Vec3 n = face_normal(m.vertex(tri, 0), m.vertex(tri, 1), m.vertex(tri, 2));
    return tri.flipped() ? -n : n;
}

Bounds bounds(const void* shape) { return static_cast<const Mesh*>(shape)->box; }

}  // namespace

// A shadow ray stops at the first triangle it meets.
extern const PrimitiveFunctions functions{.read = read,
                                          .intersect = intersect,
                                          .normal = normal,
                                          .bounds = bounds,
                                          .intersect_any = intersect_any};

}  // namespace rt::mesh
