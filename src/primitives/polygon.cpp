// Polygon (ID 11): n; then n vertices. A flat polygon, concave allowed, whose inside is
// decided by the even-odd rule: a point is inside when a ray from it in the polygon's plane
// crosses the boundary an odd number of times. Self-intersecting outlines are accepted and
// the same rule defines them (the middle of a pentagram drawn with five vertices is outside).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <new>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "primitives/even_odd.h"
#include "primitives/planar.h"
#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::polygon {

namespace {

// The most vertices a polygon may have. Vertices are stored as they are read, so this is a
// sanity limit rather than an allocation size.
constexpr long kMaxVertices = 1'000'000;

// From this many vertices on, a polygon files its edges in bands (EdgeBands).
constexpr std::size_t kBandedFrom = 16;
// The bands' lists hold at most this many entries per edge in all; fewer bands are made
// where the edges span more of them (a star whose every edge crosses the middle).
constexpr std::size_t kBandEntriesPerEdge = 8;

// A vertex may lie off the polygon's plane by this fraction of the polygon's size (the
// diagonal of its bounding box). That admits vertices written with six significant digits
// while refusing any bend that could show in an image.
constexpr double kCoplanarTolerance = 1e-4;

// The vertices span no plane when the farthest of them from the line through the two
// farthest apart is closer to it than this fraction of their distance.
constexpr double kCollinearTolerance = 1e-12;

// The edges of a many-sided outline filed by bands of v, so that a point's crossing count
// asks only the edges whose v-range reaches its band instead of all of them. The band of a
// v is floor((v - origin) * scale), clamped to the last band: every step is monotonic in v,
// so an edge whose ends span [lo, hi] is filed in every band that a v between them can
// fall in, however the steps round. The edges a point counts are then among those of its
// band, and the toggles of the even-odd count commute, so the answer is exactly the one
// every edge gives. Empty (no bands) for a polygon with few vertices.
struct EdgeBands {
    double origin = 0;  // the outline's lowest v
    double scale = 0;
    std::uint32_t count = 0;               // bands
    const std::uint32_t* first = nullptr;  // per band, where its edges start in `edges`; the end
    const std::uint32_t* edges = nullptr;  // edge i runs from outline[i] to the vertex before it

    std::size_t bands() const { return count; }
    std::size_t band_of(double v) const {
        const double x = (v - origin) * scale;  // >= 0 for v >= origin
        const std::size_t last = bands() - 1;
        return x < static_cast<double>(last) ? static_cast<std::size_t>(x) : last;
    }
};

// Placed in the reader's arena with its arrays (the outline right after it, then the bands'),
// so a polygon costs one placement rather than three allocations of fresh heap.
struct Polygon {
    Plane plane;
    int u_axis, v_axis;  // the two world axes the polygon is projected onto
    std::uint32_t vertex_count;
    const Point2* outline;  // vertex_count points
    // Outside this box no point is inside: most points the walk offers are decided by it,
    // without an edge's division (even_odd.h).
    OutlineBox outline_box;
    EdgeBands bands;
    Bounds box;
};
static_assert(std::is_trivially_destructible_v<Polygon>);

// The axis (0, 1, 2 for x, y, z) of the largest component.
int largest_axis(const Vec3& v) {
    if (v.x >= v.y && v.x >= v.z) return 0;
    return v.y >= v.z ? 1 : 2;
}

Point2 project(const Vec3& p, int u_axis, int v_axis) { return {p[u_axis], p[v_axis]}; }

// The even-odd rule: whether an odd number of edges cross the ray from p along +u.
bool even_odd_inside(const Polygon& polygon, Point2 p) {
    const std::span<const Point2> outline(polygon.outline, polygon.vertex_count);
    const std::size_t n = outline.size();
    if (!polygon.outline_box.may_hold(p)) return false;
    bool inside = false;
    const EdgeBands& bands = polygon.bands;
    if (bands.bands() == 0) {
        for (std::size_t i = 0, j = n - 1; i < n; j = i++)
            if (crosses(outline[i], outline[j], p)) inside = !inside;
        return inside;
    }
    const std::size_t band = bands.band_of(p.v);
    for (std::uint32_t k = bands.first[band]; k < bands.first[band + 1]; ++k) {
        const std::uint32_t i = bands.edges[k];
        if (crosses(outline[i], outline[i == 0 ? n - 1 : i - 1], p)) inside = !inside;
    }
    return inside;
}

// Files the edges of a polygon with many vertices in bands: about one band per edge, fewer
// where that would file an edge in more than kBandEntriesPerEdge bands on average. The bands'
// arrays are placed in the reader's arena.
void file_edges(Polygon& polygon, SceneReader& reader) {
    const std::span<const Point2> outline(polygon.outline, polygon.vertex_count);
    const std::size_t n = outline.size();
    if (n < kBandedFrom) return;
    EdgeBands bands;
    // The outline's extent in v, as its box (even_odd.h) already holds it.
    bands.origin = polygon.outline_box.v_low;
    const double extent = polygon.outline_box.v_high - bands.origin;
    if (!(extent > 0) || !std::isfinite(extent)) return;
    auto span = [&](std::size_t i) {
        const double a = outline[i].v, b = outline[i == 0 ? n - 1 : i - 1].v;
        return std::pair{bands.band_of(std::fmin(a, b)), bands.band_of(std::fmax(a, b))};
    };
    std::vector<std::uint32_t> first;
    for (std::size_t count = n; count >= 2; count /= 2) {
        bands.scale = static_cast<double>(count) / extent;
        bands.count = static_cast<std::uint32_t>(count);
        first.assign(count + 1, 0);
        std::size_t entries = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const auto [lo, hi] = span(i);
            entries += hi - lo + 1;
            for (std::size_t b = lo; b <= hi; ++b) ++first[b + 1];
            if (entries > kBandEntriesPerEdge * n) break;
        }
        if (!std::isfinite(bands.scale) || entries > kBandEntriesPerEdge * n) continue;
        for (std::size_t b = 0; b < count; ++b) first[b + 1] += first[b];
        auto* room = static_cast<std::uint32_t*>(reader.shape_room(
            (first.size() + entries) * sizeof(std::uint32_t), alignof(std::uint32_t)));
        std::uint32_t* edges = std::copy(first.begin(), first.end(), room);
        std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
        for (std::size_t i = 0; i < n; ++i) {
            const auto [lo, hi] = span(i);
            for (std::size_t b = lo; b <= hi; ++b) edges[next[b]++] = static_cast<std::uint32_t>(i);
        }
        bands.first = room;
        bands.edges = edges;
        polygon.bands = bands;
        return;
    }
}

ShapeData read(SceneReader& reader) {
    const long count = reader.whole("polygon vertex count", 3, kMaxVertices);
    // Read one vertex at a time: the count alone never decides how much is allocated (room
    // for a few is made at once, so that a small polygon's arrays are allocated once).
    constexpr long kReservedVertices = 16;
    std::vector<Vec3> vertices;
    std::vector<Location> places;
    vertices.reserve(static_cast<std::size_t>(std::min(count, kReservedVertices)));
    places.reserve(vertices.capacity());
    Bounds box;
    // The vertex's name for messages, written in place: "polygon vertex 12" is longer than
    // a std::string holds without allocating, and a gear has thousands of vertices.
    char what[32] = "polygon vertex ";
    constexpr std::size_t kPrefix = sizeof "polygon vertex " - 1;
    for (long i = 0; i < count; ++i) {
        places.push_back(reader.next_location());
        const auto end = std::to_chars(what + kPrefix, what + sizeof what, i).ptr;
        vertices.push_back(reader.vec3({what, static_cast<std::size_t>(end - what)}));
        box.expand(vertices.back());
    }

    // The plane through the two vertices farthest apart along the box's longest side and
    // the vertex farthest from the line through them: it holds for any outline, even one
    // whose signed area is zero.
    const Vec3 extent = box.max - box.min;
    const int long_axis = largest_axis(extent);
    std::size_t lo = 0, hi = 0;
    for (std::size_t i = 1; i < vertices.size(); ++i) {
        if (vertices[i][long_axis] < vertices[lo][long_axis]) lo = i;
        if (vertices[i][long_axis] > vertices[hi][long_axis]) hi = i;
    }
    const Vec3 base = vertices[lo];
    const Vec3 along = vertices[hi] - base;
    Vec3 best_cross;
    for (const Vec3& v : vertices) {
        const Vec3 c = cross(along, v - base);
        if (length_squared(c) > length_squared(best_cross)) best_cross = c;
    }
    // |along x (v - base)| is |along| times v's distance from the line.
    const double along_length = length(along);
    if (!(length(best_cross) > kCollinearTolerance * along_length * along_length))
        reader.fail(places[0], "polygon vertices all lie on one line, so they span no plane");
    Vec3 n = normalized(best_cross);
    // Orient the normal as the outline winds (counter-clockwise seen from its tip) when the
    // outline has a winding, by Newell's area vector.
    Vec3 area;
    for (std::size_t i = 0, j = vertices.size() - 1; i < vertices.size(); j = i++)
        area += cross(vertices[j] - base, vertices[i] - base);
    if (dot(area, n) < 0) n = -n;

    const double size = length(extent);
    const double offset = dot(n, base);
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        const double off = std::fabs(dot(n, vertices[i]) - offset);
        if (off > kCoplanarTolerance * size)
            reader.fail(places[i], "polygon vertex " + std::to_string(i) +
                                       " is not in the plane of the others: it is " +
                                       format_number(off) + " away, more than " +
                                       format_number(kCoplanarTolerance) +
                                       " of the polygon's size " + format_number(size));
    }

    // Project onto the two axes the plane faces least, where the outline is largest.
    const int drop = largest_axis({std::fabs(n.x), std::fabs(n.y), std::fabs(n.z)});
    const int u_axis = (drop + 1) % 3, v_axis = (drop + 2) % 3;
    static_assert(sizeof(Polygon) % alignof(Point2) == 0);
    auto* room = static_cast<std::byte*>(
        reader.shape_room(sizeof(Polygon) + vertices.size() * sizeof(Point2), alignof(Polygon)));
    auto* outline = reinterpret_cast<Point2*>(room + sizeof(Polygon));
    for (std::size_t i = 0; i < vertices.size(); ++i)
        ::new (static_cast<void*>(outline + i)) Point2(project(vertices[i], u_axis, v_axis));
    auto* polygon = ::new (static_cast<void*>(room))
        Polygon{.plane = {n, offset},
                .u_axis = u_axis,
                .v_axis = v_axis,
                .vertex_count = static_cast<std::uint32_t>(vertices.size()),
                .outline = outline,
                .outline_box = OutlineBox::of({outline, vertices.size()}),
                .bands = {},
                .box = box};
    file_edges(*polygon, reader);
    return reader.placed_shape_data(polygon);
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    const auto& p = *static_cast<const Polygon*>(shape);
    const auto t = p.plane.distance(ray, range);
    if (!t) return false;
    // The hit point's two components the outline is in, by an indexed load rather than
    // through ray.at() and Vec3's operator[] (whose selects cost more than the rest): the
    // same products and sums for those two, so the same point.
    static_assert(sizeof(Vec3) == 3 * sizeof(double) && std::is_trivially_copyable_v<Vec3>);
    double origin[3], direction[3];
    std::memcpy(origin, &ray.origin, sizeof origin);
    std::memcpy(direction, &ray.direction, sizeof direction);
    const Point2 at{origin[p.u_axis] + direction[p.u_axis] * *t,
                    origin[p.v_axis] + direction[p.v_axis] * *t};
    if (!even_odd_inside(p, at)) return false;
    hit = {*t, 0};
    return true;
}

Vec3 normal(const void* shape, const Vec3&, const Hit&) {
    return static_cast<const Polygon*>(shape)->plane.normal;
}

Bounds bounds(const void* shape) { return static_cast<const Polygon*>(shape)->box; }

std::vector<Vec3> corners(const void* shape) {
    const auto& p = *static_cast<const Polygon*>(shape);
    const int drop = 3 - p.u_axis - p.v_axis;
    std::vector<Vec3> out;
    out.reserve(p.vertex_count);
    for (const Point2& q : std::span(p.outline, p.vertex_count)) {
        double v[3];
        v[p.u_axis] = q.u;
        v[p.v_axis] = q.v;
        v[drop] =
            (p.plane.offset - p.plane.normal[p.u_axis] * q.u - p.plane.normal[p.v_axis] * q.v) /
            p.plane.normal[drop];
        out.push_back({v[0], v[1], v[2]});
    }
    return out;
}

}  // namespace

extern const PrimitiveFunctions functions{
    .read = read, .intersect = intersect, .normal = normal, .bounds = bounds, .corners = corners};

}  // namespace rt::polygon
