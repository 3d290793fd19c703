// The flat primitives of part 1: plane (2), disk (3), annulus (4), triangle (5) and
// parallelogram (6), against closed forms worked out here independently of planar.h: the
// distance to the plane from the signed height of the ray's origin above it, and containment
// from cross products (barycentric coordinates as ratios of areas), not the code's EdgeFrame.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "random_rays.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

// A surface to follow a primitive in scene text.
const char* const kSurface = "  100  1 1 1  0 1  1  0 1";

// Hits closer than this to the ray's origin are not looked for.
constexpr double kTMin = 1e-9;

// Where a ray meets the plane through `on_plane` with normal n (any length): the origin sits
// at signed height h = (o - on_plane).n / |n| above the plane, and each unit along the ray
// changes the height by d.n / |n|, so the ray reaches the plane at t = -h / (d.n / |n|).
// Nothing for a ray exactly parallel to the plane or a crossing behind kTMin.
std::optional<double> plane_crossing(const Vec3& on_plane, const Vec3& n, const Ray& ray) {
    const double n_length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    const double height = dot(ray.origin - on_plane, n) / n_length;
    const double climb = dot(ray.direction, n) / n_length;
    if (climb == 0) return std::nullopt;
    const double t = -height / climb;
    if (!(t > kTMin)) return std::nullopt;
    return t;
}

// How accurately the code's distance can agree with the closed form: rounding in the
// origin's coordinates, magnified by 1 / |cos| of the angle between the ray and the normal.
double distance_tolerance(const Ray& ray, const Vec3& unit_normal, double t) {
    const double cos = std::fabs(dot(ray.direction, unit_normal));
    return 1e-12 * (1 + max_abs_component(ray.origin) + t) / cos;
}

// A unit vector perpendicular to n.
Vec3 perpendicular(const Vec3& n) {
    const Vec3 helper = std::fabs(n.x) < 0.6 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    return normalized(cross(n, helper));
}

// A ray toward `aim` from a random origin: both sides of the shape's plane, from near and far.
Ray ray_toward(Random& random, const Vec3& aim) {
    const Vec3 origin = aim + random.unit_vector() * random.uniform(0.5, 15);
    return {origin, normalized(aim - origin)};
}

// Barycentric coordinates of a point p in the plane of the triangle (v0, v1, v2): each is
// the signed area of the triangle p makes with the opposite edge over the whole area, from
// cross products.
struct Barycentric {
    double w0, w1, w2;
};
Barycentric barycentric(const Vec3& v0, const Vec3& v1, const Vec3& v2, const Vec3& p) {
    const Vec3 n = cross(v1 - v0, v2 - v0);
    const double area2 = dot(n, n);
    return {dot(cross(v2 - v1, p - v1), n) / area2, dot(cross(v0 - v2, p - v2), n) / area2,
            dot(cross(v1 - v0, p - v0), n) / area2};
}

// Coordinates (alpha, beta) of a point p = v + alpha a + beta b in the parallelogram's plane,
// by Cramer's rule with cross products: (p - v) x b = alpha (a x b), a x (p - v) = beta (a x b).
struct EdgeCoordinates {
    double alpha, beta;
};
EdgeCoordinates edge_coordinates(const Vec3& v, const Vec3& a, const Vec3& b, const Vec3& p) {
    const Vec3 n = cross(a, b);
    const double area2 = dot(n, n);
    return {dot(cross(p - v, b), n) / area2, dot(cross(a, p - v), n) / area2};
}

// Checks one shape against the closed form for one ray, given the distance to its plane (or
// nothing) and whether that crossing lies on the shape. Returns whether the shape was hit.
bool check_ray(const Shape& shape, const Ray& ray, std::optional<double> crossing, bool on_shape,
               const Vec3& unit_normal) {
    const auto hit = first_hit(shape, ray);
    const bool expected = crossing.has_value() && on_shape;
    CHECK_EQ(hit.has_value(), expected);
    if (!hit || !expected) return false;
    CHECK_NEAR(hit->t, *crossing, distance_tolerance(ray, unit_normal, *crossing));
    const Vec3 p = ray.at(hit->t);
    // The normal is the outward one whichever side the ray comes from.
    CHECK_NEAR(shape.normal(p, *hit), unit_normal, 1e-12);
    CHECK(shape.bounds().contains(p, 1e-9 * (1 + max_abs_component(p))));
    // The early stop: a best-so-far just short of the hit hides it; just beyond, it is found.
    Hit other{-1, -1};
    CHECK(!shape.intersect(ray, {kTMin, hit->t * (1 - 1e-9)}, other));
    CHECK_EQ(other.t, -1.0);  // left alone
    CHECK(shape.intersect(ray, {kTMin, hit->t * (1 + 1e-9) + 1e-12}, other));
    return true;
}

// Where a crossing lies against a flat shape's outline; `edge`: too close to it to tell which
// side the code's rounding puts the crossing.
enum class Place { on, off, edge };

// Checks one ray against a flat shape in the plane through `on_plane` with normal n (any
// length), whose outline place(p, t) decides for the crossing point p at distance t, and
// counts it; a crossing at an edge is skipped.
template <typename Where>
void check_flat_ray(const Shape& shape, const Ray& ray, const Vec3& on_plane, const Vec3& n,
                    RayCounts& counts, const Where& place) {
    const auto crossing = plane_crossing(on_plane, n, ray);
    bool on_shape = false;
    if (crossing) {
        const Place at = place(ray.at(*crossing), *crossing);
        if (at == Place::edge) {
            ++counts.skipped;
            return;
        }
        on_shape = at == Place::on;
    }
    (check_ray(shape, ray, crossing, on_shape, normalized(n)) ? counts.hits : counts.misses)++;
}

std::string primitive_error(const std::string& text) {
    return scene_error(join(kTestViewer, text));
}

}  // namespace

// ---------------------------------------------------------------- plane (2)

TEST(plane_random_rays_match_closed_form) {
    Random random(2);
    int hits = 0, misses = 0, from_below = 0, from_above = 0;
    for (int i = 0; i < 20000; ++i) {
        Vec3 n = random.in_box(3);
        if (length(n) < 0.05) continue;
        const double D = random.uniform(-5, 5);
        const Shape s = parse_shape(object_text(2, {D, n.x, n.y, n.z}));
        // A point on the plane: the foot of the origin, D n / |n|^2.
        const Vec3 foot = n * (D / length_squared(n));
        const Vec3 aim = foot + perpendicular(n) * random.uniform(-8, 8) +
                         cross(n, perpendicular(n)) / length(n) * random.uniform(-8, 8);
        Ray ray = ray_toward(random, aim);
        if (i % 3 == 0) ray.direction = random.unit_vector();  // hits or misses at random
        const auto crossing = plane_crossing(foot, n, ray);
        if (check_ray(s, ray, crossing, true, normalized(n))) {
            ++hits;
            (dot(ray.origin, n) < D ? from_below : from_above)++;
            CHECK_NEAR(dot(ray.at(*crossing), n) / length(n), D / length(n),
                       1e-11 * (1 + max_abs_component(ray.origin)));
        } else {
            ++misses;
        }
    }
    CHECK(hits > 10000);
    CHECK(misses > 2000);
    CHECK(from_below > 3000 && from_above > 3000);
}

TEST(plane_parallel_rays_never_hit_and_never_give_nan) {
    // Exactly parallel: normals along an axis, directions with no component along it; from
    // above, from below and lying in the plane itself.
    Random random(20);
    const Shape s = parse_shape("2  3  0 0 2");  // z = 1.5
    for (int i = 0; i < 1000; ++i) {
        const double angle = random.uniform(0, 6.3);
        const double z = i % 3 == 0 ? 1.5 : random.uniform(-4, 4);
        const Ray ray{{random.uniform(-5, 5), random.uniform(-5, 5), z},
                      {std::cos(angle), std::sin(angle), 0}};
        Hit hit{-1, -1};
        CHECK(!s.intersect(ray, {kTMin, kInfinity}, hit));
        CHECK_EQ(hit.t, -1.0);
    }
    // Nearly parallel, for a normal no direction can be exactly perpendicular to: any hit
    // reported is a finite distance at which the ray really is on the plane.
    const Vec3 n{1, 2, 3};
    const Shape tilted = parse_shape("2  1  1 2 3");
    int far_hits = 0;
    for (int i = 0; i < 1000; ++i) {
        const Vec3 along = normalized(cross(n, random.unit_vector()));
        const Ray ray{random.in_box(5), along};
        const auto hit = first_hit(tilted, ray);
        if (!hit) continue;
        ++far_hits;
        CHECK(std::isfinite(hit->t));
        const Vec3 normal = tilted.normal(ray.at(hit->t), *hit);
        CHECK(!std::isnan(normal.x) && !std::isnan(normal.y) && !std::isnan(normal.z));
    }
    // Rounding leaves most such rays a little off parallel, meeting the plane far away.
    CHECK(far_hits > 100);
}

TEST(plane_inside_is_the_half_space_below) {
    Random random(21);
    for (int i = 0; i < 2000; ++i) {
        const Vec3 n = random.in_box(3);
        if (length(n) < 0.05) continue;
        const double D = random.uniform(-5, 5);
        const Shape s = parse_shape(object_text(2, {D, n.x, n.y, n.z}));
        CHECK(s.has_inside());
        const Vec3 x = random.in_box(10);
        const double height = (dot(n, x) - D) / length(n);
        if (std::fabs(height) < 1e-9) continue;
        CHECK_EQ(s.inside(x), height < 0);
    }
    const Shape floor = parse_shape("2  0  0 1 0");
    CHECK(floor.inside({0, -1, 0}));
    CHECK(!floor.inside({5, 1, -3}));
    CHECK(!floor.inside({5, 0, -3}));  // the plane itself is not inside (strictly n.x < D)
}

TEST(plane_scaled_normal_and_offset_is_the_same_plane) {
    Random random(22);
    for (int i = 0; i < 500; ++i) {
        const Vec3 n = random.in_box(3);
        if (length(n) < 0.05) continue;
        const double D = random.uniform(-5, 5);
        const double k = random.uniform(0.001, 1000);
        const Shape s = parse_shape(object_text(2, {D, n.x, n.y, n.z}));
        const Shape scaled = parse_shape(object_text(2, {k * D, k * n.x, k * n.y, k * n.z}));
        // Scaling by a negative number keeps the points but turns the plane over.
        const Shape flipped = parse_shape(object_text(2, {-k * D, -k * n.x, -k * n.y, -k * n.z}));
        const Ray ray{random.in_box(8), random.unit_vector()};
        const auto a = first_hit(s, ray), b = first_hit(scaled, ray), c = first_hit(flipped, ray);
        CHECK_EQ(a.has_value(), b.has_value());
        CHECK_EQ(a.has_value(), c.has_value());
        if (a && b && c) {
            CHECK_NEAR(b->t, a->t, 1e-9 * (1 + a->t));
            CHECK_NEAR(c->t, a->t, 1e-9 * (1 + a->t));
            const Vec3 p = ray.at(a->t);
            CHECK_NEAR(scaled.normal(p, *b), s.normal(p, *a), 1e-12);
            CHECK_NEAR(flipped.normal(p, *c), -s.normal(p, *a), 1e-12);
        }
        const Vec3 x = random.in_box(8);
        if (std::fabs(dot(n, x) - D) > 1e-9 * length(n)) {
            CHECK_EQ(scaled.inside(x), s.inside(x));
            CHECK_EQ(flipped.inside(x), !s.inside(x));
        }
    }
}

TEST(plane_bounds_are_infinite) {
    const Bounds b = parse_shape("2  1  0 0 1").bounds();
    CHECK(b.contains({1e300, -1e300, 1}));
}

TEST(plane_hit_behind_the_origin_is_not_reported) {
    const Shape s = parse_shape("2  -2  0 0 1");  // z = -2
    CHECK(!first_hit(s, {{0, 0, 0}, {0, 0, 1}}));
    const auto hit = first_hit(s, {{0, 0, 0}, {0, 0, -1}});
    CHECK(hit.has_value());
    if (hit) CHECK_NEAR(hit->t, 2, 1e-15);
}

// ---------------------------------------------------------------- disk (3)

TEST(disk_random_rays_match_closed_form) {
    Random random(3);
    RayCounts counts;
    for (int i = 0; i < 20000; ++i) {
        const Vec3 c = random.in_box(5);
        const Vec3 n = random.in_box(2);
        if (length(n) < 0.05) continue;
        const double r = random.uniform(0.1, 3);
        const Shape s = parse_shape(object_text(3, {c.x, c.y, c.z, n.x, n.y, n.z, r}));
        // Aim within 1.5 radii of the centre in the disk's plane, so both hits and misses occur.
        const Vec3 u = perpendicular(n), v = cross(normalized(n), u);
        const Vec3 aim =
            c + u * random.uniform(-1.5 * r, 1.5 * r) + v * random.uniform(-1.5 * r, 1.5 * r);
        Ray ray = ray_toward(random, aim);
        if (i % 4 == 0) ray.direction = random.unit_vector();
        check_flat_ray(s, ray, c, n, counts, [&](const Vec3& p, double t) {
            const double from_centre = length(p - c);
            if (std::fabs(from_centre - r) < 1e-9 * (1 + t)) return Place::edge;
            return from_centre <= r ? Place::on : Place::off;
        });
    }
    CHECK(counts.hits > 4000);
    CHECK(counts.misses > 4000);
    CHECK(counts.skipped < 10);
}

TEST(disk_rim_and_parallel_rays) {
    // Radius 2 around (1, 1, 1) in the plane z = 1.
    const Shape s = parse_shape("3  1 1 1  0 0 3  2");
    // Steep rays just inside and just outside the rim.
    for (const double angle : {0.0, 0.7, 2.0, 4.0}) {
        const Vec3 rim{1 + 2 * std::cos(angle), 1 + 2 * std::sin(angle), 1};
        const Vec3 outward{std::cos(angle), std::sin(angle), 0};
        const Vec3 inside = rim - outward * 1e-7, outside = rim + outward * 1e-7;
        CHECK(first_hit(s, {inside + Vec3(0.3, 0, 5), normalized(Vec3(-0.3, 0, -5))}));
        CHECK(!first_hit(s, {outside + Vec3(0.3, 0, 5), normalized(Vec3(-0.3, 0, -5))}));
        // From below, the same.
        CHECK(first_hit(s, {inside - Vec3(0, 0.2, 5), normalized(Vec3(0, 0.2, 5))}));
        CHECK(!first_hit(s, {outside - Vec3(0, 0.2, 5), normalized(Vec3(0, 0.2, 5))}));
        // Grazing: a ray at 1/1000 rad to the plane, crossing it just inside the rim.
        const Vec3 grazing = normalized(outward * -1 + Vec3(0, 0, -1e-3));
        const auto hit = first_hit(s, {inside - grazing * 3, grazing});
        CHECK(hit.has_value());
        if (hit) CHECK_NEAR(hit->t, 3, 1e-6);
    }
    // Parallel to the disk, in its plane and beside it: no hit, the hit left alone.
    Hit hit{-1, -1};
    CHECK(!s.intersect({{-5, 1, 1}, {1, 0, 0}}, {kTMin, kInfinity}, hit));
    CHECK(!s.intersect({{-5, 1, 1.5}, {1, 0, 0}}, {kTMin, kInfinity}, hit));
    CHECK_EQ(hit.t, -1.0);
}

TEST(disk_bounds_touch_the_rim) {
    // The box must contain every rim point and, along each axis, reach no further than the
    // rim does (found here by walking the rim, not by the formula in disk_bounds).
    Random random(30);
    for (int i = 0; i < 200; ++i) {
        const Vec3 c = random.in_box(5);
        const Vec3 n = i % 10 == 0 ? Vec3(0, 0, 1) : random.unit_vector();
        const double r = random.uniform(0.1, 3);
        const Shape s = parse_shape(object_text(3, {c.x, c.y, c.z, n.x, n.y, n.z, r}));
        const Bounds b = s.bounds();
        const Vec3 u = perpendicular(n), v = cross(n, u);
        Bounds walked;
        const int steps = 20000;
        for (int k = 0; k < steps; ++k) {
            const double angle = 2 * std::numbers::pi * k / steps;
            const Vec3 rim = c + (u * std::cos(angle) + v * std::sin(angle)) * r;
            CHECK(b.contains(rim, 1e-12));
            walked.expand(rim);
        }
        // The walk misses the true extreme by at most r (1 - cos(pi / steps)).
        const double gap = r * (1 - std::cos(std::numbers::pi / steps)) + 1e-12;
        CHECK_NEAR(b.min, walked.min, gap);
        CHECK_NEAR(b.max, walked.max, gap);
    }
    // A disk facing along z is flat in z.
    const Bounds flat = parse_shape("3  1 2 3  0 0 1  2").bounds();
    CHECK_NEAR(flat.min, Vec3(-1, 0, 3), 1e-15);
    CHECK_NEAR(flat.max, Vec3(3, 4, 3), 1e-15);
}

// ---------------------------------------------------------------- annulus (4)

TEST(annulus_random_rays_match_closed_form) {
    Random random(4);
    RayCounts counts;
    int in_hole = 0;
    for (int i = 0; i < 20000; ++i) {
        const Vec3 c = random.in_box(5);
        const Vec3 n = random.in_box(2);
        if (length(n) < 0.05) continue;
        const double outer = random.uniform(0.2, 3);
        const double inner = i % 10 == 0 ? 0 : random.uniform(0, 0.9) * outer;
        const Shape s = parse_shape(object_text(4, {c.x, c.y, c.z, n.x, n.y, n.z, outer, inner}));
        const Vec3 u = perpendicular(n), v = cross(normalized(n), u);
        const Vec3 aim = c + u * random.uniform(-1.3 * outer, 1.3 * outer) +
                         v * random.uniform(-1.3 * outer, 1.3 * outer);
        Ray ray = ray_toward(random, aim);
        if (i % 4 == 0) ray.direction = random.unit_vector();
        check_flat_ray(s, ray, c, n, counts, [&](const Vec3& p, double t) {
            const double from_centre = length(p - c);
            const double margin = 1e-9 * (1 + t);
            if (std::fabs(from_centre - outer) < margin || std::fabs(from_centre - inner) < margin)
                return Place::edge;
            if (from_centre < inner) ++in_hole;
            return from_centre <= outer && from_centre >= inner ? Place::on : Place::off;
        });
    }
    CHECK(counts.hits > 4000);
    CHECK(counts.misses > 4000);
    CHECK(in_hole > 1000);
    CHECK(counts.skipped < 10);
}

TEST(annulus_edges) {
    // Radii 1 and 3 around the origin in the plane y = 0; rays straight down.
    const Shape s = parse_shape("4  0 0 0  0 1 0  3 1");
    auto down_at = [&](double x) { return first_hit(s, {{x, 5, 0}, {0, -1, 0}}); };
    CHECK(!down_at(0));  // the hole's centre
    CHECK(!down_at(1 - 1e-9));
    CHECK(down_at(1 + 1e-9));
    CHECK(down_at(2));
    CHECK(down_at(3 - 1e-9));
    CHECK(!down_at(3 + 1e-9));
    CHECK(!down_at(-0.5));
    CHECK(down_at(-2.5));
    // A ray through the hole at a slant misses; one from below through the ring hits.
    CHECK(!first_hit(s, {{-0.5, 1, 0}, normalized(Vec3(1, -1, 0))}));
    const auto below = first_hit(s, {{2, -4, 0}, {0, 1, 0}});
    CHECK(below.has_value());
    if (below) {
        CHECK_NEAR(below->t, 4, 1e-15);
        CHECK_NEAR(s.normal({2, 0, 0}, *below), Vec3(0, 1, 0), 1e-15);
    }
    // An inner radius of 0 leaves no hole.
    CHECK(first_hit(parse_shape("4  0 0 0  0 1 0  3 0"), {{0, 5, 0}, {0, -1, 0}}));
    // Bounds are the outer disk's.
    const Bounds b = s.bounds();
    CHECK_NEAR(b.min, Vec3(-3, 0, -3), 1e-15);
    CHECK_NEAR(b.max, Vec3(3, 0, 3), 1e-15);
}

// ---------------------------------------------------------------- triangle (5)

TEST(triangle_random_rays_match_closed_form) {
    Random random(5);
    RayCounts counts;
    for (int i = 0; i < 20000; ++i) {
        const Vec3 v0 = random.in_box(4), v1 = random.in_box(4), v2 = random.in_box(4);
        const Vec3 n = cross(v1 - v0, v2 - v0);
        // Skip slivers: their containment is too sensitive to rounding to compare.
        if (length(n) < 0.05 * length(v1 - v0) * length(v2 - v0)) continue;
        const Shape s =
            parse_shape(object_text(5, {v0.x, v0.y, v0.z, v1.x, v1.y, v1.z, v2.x, v2.y, v2.z}));
        // Aim at edge coordinates in [-0.2, 1], so hits and misses both occur.
        const double a = random.uniform(-0.2, 1), b = random.uniform(-0.2, 1);
        const Vec3 aim = v0 + (v1 - v0) * a + (v2 - v0) * b;
        Ray ray = ray_toward(random, aim);
        if (i % 5 == 0) ray.direction = random.unit_vector();
        check_flat_ray(s, ray, v0, n, counts, [&](const Vec3& p, double t) {
            const Barycentric w = barycentric(v0, v1, v2, p);
            const double nearest_edge =
                std::min({std::fabs(w.w0), std::fabs(w.w1), std::fabs(w.w2)});
            if (nearest_edge < 1e-9 * (1 + t)) return Place::edge;
            CHECK_NEAR(w.w0 + w.w1 + w.w2, 1, 1e-9);
            return w.w0 >= 0 && w.w1 >= 0 && w.w2 >= 0 ? Place::on : Place::off;
        });
    }
    CHECK(counts.hits > 4000);
    CHECK(counts.misses > 4000);
    CHECK(counts.skipped < 10);
}

TEST(triangle_normal_follows_the_vertex_order) {
    // Counter-clockwise seen from +z: the normal is +z; reversing two vertices turns it over.
    const Shape ccw = parse_shape("5  0 0 0  2 0 0  0 2 0");
    const Shape cw = parse_shape("5  0 0 0  0 2 0  2 0 0");
    const auto a = first_hit(ccw, {{0.5, 0.5, 3}, {0, 0, -1}});
    const auto b = first_hit(cw, {{0.5, 0.5, -3}, {0, 0, 1}});
    CHECK(a.has_value() && b.has_value());
    if (a && b) {
        CHECK_NEAR(a->t, 3, 1e-15);
        CHECK_NEAR(ccw.normal({0.5, 0.5, 0}, *a), Vec3(0, 0, 1), 1e-15);
        CHECK_NEAR(cw.normal({0.5, 0.5, 0}, *b), Vec3(0, 0, -1), 1e-15);
    }
    const Bounds box = ccw.bounds();
    CHECK_NEAR(box.min, Vec3(0, 0, 0), 0);
    CHECK_NEAR(box.max, Vec3(2, 2, 0), 0);
}

TEST(triangle_edges_and_corners) {
    // The triangle (0,0,0), (4,0,0), (0,4,0) in z = 0. Points a hair inside and outside each
    // edge and corner, hit by steep rays from both sides and by grazing rays.
    const Shape s = parse_shape("5  0 0 0  4 0 0  0 4 0");
    struct Probe {
        Vec3 inside, outside;
    };
    const double e = 1e-7;
    const Probe probes[] = {
        {{2, e, 0}, {2, -e, 0}},                 // edge v0 v1
        {{e, 2, 0}, {-e, 2, 0}},                 // edge v0 v2
        {{2 - e, 2 - e, 0}, {2 + e, 2 + e, 0}},  // edge v1 v2 (the hypotenuse)
        {{e, e, 0}, {-e, -e, 0}},                // corner v0
        {{4 - 3 * e, e, 0}, {4 + e, 0, 0}},      // corner v1
        {{e, 4 - 3 * e, 0}, {0, 4 + e, 0}},      // corner v2
    };
    for (const Probe& p : probes) {
        for (const double side : {1.0, -1.0}) {
            const Vec3 slant = normalized(Vec3(0.3, -0.2, -side));
            CHECK(first_hit(s, {p.inside - slant * 5, slant}));
            CHECK(!first_hit(s, {p.outside - slant * 5, slant}));
        }
        // Grazing along the plane at 1/1000 rad, from the middle of the triangle outward.
        const Vec3 out = normalized(p.outside - Vec3(1, 1, 0));
        const Vec3 grazing = normalized(Vec3(out.x, out.y, -1e-3));
        const auto graze_in = first_hit(s, {p.inside - grazing * 2, grazing});
        CHECK(graze_in.has_value());
        if (graze_in) CHECK_NEAR(graze_in->t, 2, 1e-6);
        CHECK(!first_hit(s, {p.outside - grazing * 2, grazing}));
    }
    // Parallel to the triangle: in its plane and above it.
    CHECK(!first_hit(s, {{-1, 1, 0}, {1, 0, 0}}));
    CHECK(!first_hit(s, {{-1, 1, 0.5}, {1, 0, 0}}));
}

TEST(triangles_sharing_an_edge_leave_no_gap_beside_it) {
    // A flat quadrilateral split along its diagonal b c: rays aimed a hair (1e-9 of the
    // diagonal's length) to either side of the diagonal hit the triangle on that side, and
    // rays aimed at the diagonal itself hit at least one of the two (the test is watertight:
    // both triangles decide the side of their shared edge from the same numbers).
    Random random(50);
    for (int i = 0; i < 200; ++i) {
        const Vec3 a = random.in_box(3), b = random.in_box(3), c = random.in_box(3);
        const Vec3 d = b + c - a;  // opposite a across the diagonal
        if (length(cross(b - a, c - a)) < 0.05 * length(b - a) * length(c - a)) continue;
        const Shape first =
            parse_shape(object_text(5, {a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z}));
        const Shape second =
            parse_shape(object_text(5, {b.x, b.y, b.z, d.x, d.y, d.z, c.x, c.y, c.z}));
        // In the plane, perpendicular to the diagonal, toward a.
        const Vec3 diagonal = c - b;
        const Vec3 to_a = a - b;
        const Vec3 toward_a =
            normalized(to_a - diagonal * (dot(to_a, diagonal) / dot(diagonal, diagonal)));
        const Vec3 step = toward_a * (1e-9 * length(diagonal));
        for (int k = 0; k < 50; ++k) {
            const Vec3 on_edge = b + diagonal * random.uniform(0.01, 0.99);
            const Ray ray_a = ray_toward(random, on_edge + step);
            CHECK(first_hit(first, ray_a).has_value());
            CHECK(!first_hit(second, ray_a).has_value());
            const Ray ray_d = ray_toward(random, on_edge - step);
            CHECK(first_hit(second, ray_d).has_value());
            CHECK(!first_hit(first, ray_d).has_value());
            const Ray ray_edge = ray_toward(random, on_edge);
            CHECK(first_hit(first, ray_edge) || first_hit(second, ray_edge));
        }
    }
}

// ---------------------------------------------------------------- parallelogram (6)

TEST(parallelogram_random_rays_match_closed_form) {
    Random random(6);
    RayCounts counts;
    for (int i = 0; i < 20000; ++i) {
        const Vec3 v = random.in_box(4), a = random.in_box(3), b = random.in_box(3);
        const Vec3 n = cross(a, b);
        if (length(n) < 0.05 * length(a) * length(b)) continue;
        const Shape s = parse_shape(object_text(6, {v.x, v.y, v.z, a.x, a.y, a.z, b.x, b.y, b.z}));
        const Vec3 aim = v + a * random.uniform(-0.3, 1.3) + b * random.uniform(-0.3, 1.3);
        Ray ray = ray_toward(random, aim);
        if (i % 5 == 0) ray.direction = random.unit_vector();
        check_flat_ray(s, ray, v, n, counts, [&](const Vec3& p, double t) {
            const EdgeCoordinates q = edge_coordinates(v, a, b, p);
            const double nearest_edge = std::min({std::fabs(q.alpha), std::fabs(1 - q.alpha),
                                                  std::fabs(q.beta), std::fabs(1 - q.beta)});
            if (nearest_edge < 1e-9 * (1 + t)) return Place::edge;
            const bool inside = q.alpha >= 0 && q.alpha <= 1 && q.beta >= 0 && q.beta <= 1;
            return inside ? Place::on : Place::off;
        });
    }
    CHECK(counts.hits > 4000);
    CHECK(counts.misses > 4000);
    CHECK(counts.skipped < 10);
}

TEST(parallelogram_edges_corners_and_bounds) {
    // A slanted parallelogram from (1, 0, 0) with edges (2, 0, 0) and (1, 3, 0), in z = 0.
    const Shape s = parse_shape("6  1 0 0  2 0 0  1 3 0");
    const double e = 1e-7;
    // Near each of the four corners, just inside and just outside along the diagonals.
    const Vec3 corners[] = {{1, 0, 0}, {3, 0, 0}, {2, 3, 0}, {4, 3, 0}};
    const Vec3 centre{2.5, 1.5, 0};
    for (const Vec3& corner : corners) {
        const Vec3 toward_centre = normalized(centre - corner);
        for (const double side : {1.0, -1.0}) {
            const Vec3 down{0, 0, -side};
            CHECK(first_hit(s, {corner + toward_centre * e - down * 4, down}));
            CHECK(!first_hit(s, {corner - toward_centre * e - down * 4, down}));
        }
    }
    // Along the slanted edge from (1, 0, 0) to (2, 3, 0): alpha = 0.
    const Vec3 across = normalized(Vec3(3, -1, 0));  // perpendicular to (1, 3, 0), pointing in
    const Vec3 mid{1.5, 1.5, 0};
    CHECK(first_hit(s, {mid + across * e + Vec3(0, 0, 2), {0, 0, -1}}));
    CHECK(!first_hit(s, {mid - across * e + Vec3(0, 0, 2), {0, 0, -1}}));
    // The normal is a x b normalised: +z here.
    const auto hit = first_hit(s, {{2.5, 1.5, -2}, {0, 0, 1}});
    CHECK(hit.has_value());
    if (hit) {
        CHECK_NEAR(hit->t, 2, 1e-15);
        CHECK_NEAR(s.normal({2.5, 1.5, 0}, *hit), Vec3(0, 0, 1), 1e-15);
    }
    // Parallel rays never hit.
    CHECK(!first_hit(s, {{0, 1, 0}, {1, 0, 0}}));
    // The bounds are the four corners' box.
    const Bounds b = s.bounds();
    CHECK_NEAR(b.min, Vec3(1, 0, 0), 0);
    CHECK_NEAR(b.max, Vec3(4, 3, 0), 0);
}

// ---------------------------------------------------------------- all: the early stop

TEST(flat_primitives_stop_at_the_best_distance_so_far) {
    // Each is hit at t = 5 by a ray from (0.5, 0, 0) straight along -z (the annulus on its
    // ring, the triangle and parallelogram well inside).
    const char* const shapes[] = {
        "2  -5  0 0 1",
        "3  0 0 -5  0 0 1  1",
        "4  0 0 -5  0 0 1  2 0.25",
        "5  -1 -1 -5  2 -1 -5  -1 2 -5",
        "6  -1 -1 -5  2 0 0  0 2 0",
    };
    for (const char* text : shapes) {
        const Shape s = parse_shape(text);
        const Ray ray{{0.5, 0, 0}, {0, 0, -1}};
        Hit hit{123, 7};
        CHECK(!s.intersect(ray, {kTMin, 4.999}, hit));
        CHECK(hit.t == 123 && hit.part == 7);
        CHECK(!s.intersect(ray, {5.001, kInfinity}, hit));  // nor before t_min
        CHECK(s.intersect(ray, {kTMin, 5.001}, hit));
        CHECK_NEAR(hit.t, 5, 1e-15);
    }
}

// ---------------------------------------------------------------- read errors

TEST(flat_primitive_read_errors) {
    // Each line below is line 2 of the scene (the test viewer is line 1).
    // Plane: zero normal.
    CHECK_CONTAINS(primitive_error(join("2 1  0 0 0", kSurface)),
                   "test.in:2:6: plane normal must have a non-zero length");
    // A normal whose squared length overflows, or underflows, is still a direction.
    CHECK_EQ(primitive_error(join("2 1  1e300 0 0", kSurface)), std::string());
    CHECK_EQ(primitive_error(join("2 1  0 1e-170 0", kSurface)), std::string());
    // Disk: zero normal, zero and negative radius.
    CHECK_CONTAINS(primitive_error(join("3 0 0 0  0 0 0  1", kSurface)),
                   "test.in:2:10: disk normal must have a non-zero length");
    CHECK_CONTAINS(primitive_error(join("3 0 0 0  0 0 1  0", kSurface)),
                   "test.in:2:17: disk radius must be > 0, got 0");
    CHECK_CONTAINS(primitive_error(join("3 0 0 0  0 0 1  -1", kSurface)),
                   "test.in:2:17: disk radius must be > 0, got -1");
    // Annulus: zero normal, bad outer radius, inner radius negative, equal to or beyond the
    // outer.
    CHECK_CONTAINS(primitive_error(join("4 0 0 0  0 0 0  2 1", kSurface)),
                   "test.in:2:10: annulus normal must have a non-zero length");
    CHECK_CONTAINS(primitive_error(join("4 0 0 0  0 1 0  -2 1", kSurface)),
                   "test.in:2:17: annulus outer radius must be > 0, got -2");
    CHECK_CONTAINS(primitive_error(join("4 0 0 0  0 1 0  2 -1", kSurface)),
                   "test.in:2:19: annulus inner radius must be >= 0, got -1");
    CHECK_CONTAINS(primitive_error(join("4 0 0 0  0 1 0  2 2", kSurface)),
                   "test.in:2:19: annulus inner radius must be less than the outer radius 2, "
                   "got 2");
    CHECK_CONTAINS(primitive_error(join("4 0 0 0  0 1 0  2 3", kSurface)),
                   "test.in:2:19: annulus inner radius must be less than the outer radius 2, "
                   "got 3");
    // Triangle: collinear and coincident vertices, reported at the first vertex.
    CHECK_CONTAINS(primitive_error(join("5  0 0 0  1 1 1  3 3 3", kSurface)),
                   "test.in:2:4: triangle has zero area (its vertices are collinear)");
    CHECK_CONTAINS(primitive_error(join("5  1 2 3  1 2 3  0 0 1", kSurface)),
                   "test.in:2:4: triangle has zero area (its vertices are collinear)");
    // Parallelogram: parallel edges, a zero edge, reported at the vertex.
    CHECK_CONTAINS(primitive_error(join("6  0 0 0  1 2 0  -2 -4 0", kSurface)),
                   "test.in:2:4: parallelogram has zero area (its edges are parallel or zero)");
    CHECK_CONTAINS(primitive_error(join("6  0 0 0  0 0 0  0 1 0", kSurface)),
                   "test.in:2:4: parallelogram has zero area (its edges are parallel or zero)");
    // A number missing at the end, and a non-number.
    CHECK_CONTAINS(primitive_error("5  0 0 0  1 0 0  0 1"),
                   "test.in:2:21: unexpected end of file: expected triangle vertex 2");
    CHECK_CONTAINS(primitive_error(join("6  0 0 0  1 0 0  0 one 0", kSurface)),
                   "test.in:2:20: expected parallelogram edge b (a number), got 'one'");
    // The same shapes with sound numbers read fine.
    CHECK_EQ(primitive_error(join("4 0 0 0  0 1 0  2 0", kSurface)), std::string());
    CHECK_EQ(primitive_error(join("5  0 0 0  1 0 0  0 1 0", kSurface)), std::string());
}
