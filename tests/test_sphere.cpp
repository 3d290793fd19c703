// Sphere (ID 1) against the closed form: the geometric solution of the ray-sphere problem.
#include <cmath>

#include "accel/sphere_cull.h"
#include "primitives/sphere_test.h"
#include "random_rays.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

TEST(random_rays_match_closed_form) {
    Random random(1);
    RayCounts counts;
    int inside = 0;
    for (int i = 0; i < 20000; ++i) {
        const double r = random.uniform(0.1, 3);
        const Vec3 c = random.in_box(5);
        const Shape s = parse_shape(object_text(1, {r, c.x, c.y, c.z}));
        const Ray ray = ray_at_ball(random, c, r, i);
        const auto found = compare_first_hit(s, ray, {sphere_distance(c, r, ray)}, 1e-9, counts);
        if (!found) continue;
        if (length(ray.origin - c) < r) ++inside;
        const Vec3 p = found->point;
        CHECK_NEAR(length(p - c), r, 1e-9);
        CHECK_NEAR(s.normal(p, found->hit), (p - c) / r, 1e-9);
        CHECK(s.bounds().contains(p, 1e-9));
    }
    CHECK(counts.hits > 5000);
    CHECK(counts.misses > 5000);
    CHECK(inside > 100);
}

namespace {

// Range ends on each of a quadratic's two computed roots and one to three doubles either side.
void add_ends_around(std::vector<double>& ends, double near, double far) {
    for (const double root : {near, far}) {
        double below = root, above = root;
        ends.push_back(root);
        for (int step = 0; step < 3; ++step) {
            below = std::nextafter(below, -kInfinity);
            above = std::nextafter(above, kInfinity);
            ends.push_back(below);
            ends.push_back(above);
        }
    }
}

}  // namespace

// The early decision (quadratic_surely_out_of_range) must never drop a sphere the quadratic's
// roots would keep: on spheres from 2^-20 to 2^20 in radius, far and near, rays from inside,
// outside, on the surface and grazing, and ranges whose ends lie on the computed roots, a
// few doubles either side of them, where rounding would show, and a relative 1e-9 and 1e-13
// short of the nearer.
TEST(an_early_decision_never_drops_a_crossing) {
    Random random(77);
    int decided = 0, behind = 0, beyond = 0;
    for (int i = 0; i < 40000; ++i) {
        const double scale = std::ldexp(1.0, static_cast<int>(random.uniform(-20, 20)));
        const double r = scale * random.uniform(0.01, 1);
        const Vec3 centre = random.in_box(scale * (i % 4 == 0 ? 1e4 : 3));
        const Vec3 direction = random.unit_vector();
        Vec3 origin = centre + random.in_box(r * (i % 3 == 0 ? 0.7 : 4));
        if (i % 5 == 0) origin = centre + random.unit_vector() * r;  // on the surface
        if (i % 7 == 0) {  // grazing: the ray passes the centre at about the radius
            const Vec3 side = normalized(cross(direction, random.unit_vector()));
            origin = centre + side * (r * random.uniform(0.999999, 1.000001)) -
                     direction * (r * random.uniform(-3, 3));
        }
        const Ray ray{origin, direction};
        const SphereQuadratic k = sphere_quadratic({centre, r * r}, ray);
        if (!(k.discriminant >= 0)) continue;
        // The computed roots, then range ends on them and near them.
        double near = 0, far = 0;
        if (!quadratic_crossing(k, {-kInfinity, kInfinity}, near)) continue;
        if (!quadratic_crossing(k, {near, kInfinity}, far)) far = near;
        std::vector<double> ends{0,          1e-9 * scale,      scale * random.uniform(0, 8),
                                 near * 0.5, near * (1 - 1e-9), near * (1 - 1e-13),
                                 far * 2,    kInfinity};
        add_ends_around(ends, near, far);
        for (const double t_min : ends) {
            for (const double t_max : ends) {
                if (!(t_min >= 0) || !(t_min <= t_max)) continue;
                const Interval range{t_min, t_max};
                double t = 0;
                const bool crosses = quadratic_crossing(k, range, t);
                // The sphere's own test gives the roots' answer, to the bit.
                double sphere_t = 0;
                const bool sphere_crosses = sphere_crossing({centre, r * r}, ray, range, sphere_t);
                CHECK_EQ(sphere_crosses, crosses);
                if (crosses && sphere_crosses) CHECK_EQ(sphere_t, t);
                if (!quadratic_surely_out_of_range(k, range)) continue;
                ++decided;
                ++(k.b > 0 ? behind : beyond);
                CHECK(!crosses);
                if (crosses) return;  // one report is enough
            }
        }
    }
    // Each kind of decision was taken many times.
    CHECK(behind > 10000);
    CHECK(beyond > 10000);
}

// The same through the sphere itself: the ray toward a unit sphere 10 away is decided early
// only where both crossings (9 and 11) are out of range.
TEST(a_sphere_behind_or_beyond_is_decided_without_its_roots) {
    const SphereParameters s{{0, 0, -10}, 1};
    const Ray toward{{0, 0, 0}, {0, 0, -1}};
    const Ray away{{0, 0, 0}, {0, 0, 1}};
    const SphereQuadratic k = sphere_quadratic(s, toward);
    CHECK_EQ(k.b, -10.0);
    CHECK(quadratic_surely_out_of_range(k, {0, 8.9}));   // both beyond
    CHECK(!quadratic_surely_out_of_range(k, {0, 9.1}));  // 9 is in range
    CHECK(!quadratic_surely_out_of_range(k, {0, 9}));    // 9 exactly: too close to call
    CHECK(quadratic_surely_out_of_range(sphere_quadratic(s, away), {0, kInfinity}));  // behind
    // From the centre (c < 0), the far crossing 1 away: never decided early, whether it is
    // in range (up to 2) or beyond it (up to 0.5); the roots decide.
    const SphereQuadratic inside = sphere_quadratic(s, {{0, 0, -10}, {0, 0, -1}});
    CHECK(!quadratic_surely_out_of_range(inside, {0, 2}));
    CHECK(!quadratic_surely_out_of_range(inside, {0, 0.5}));
    double t = 0;
    CHECK(!sphere_crossing(s, away, {0, kInfinity}, t));
    CHECK(sphere_crossing(s, toward, {0, 9.5}, t));
    CHECK_EQ(t, 9.0);
    CHECK(!sphere_crossing(s, toward, {0, 8.9}, t));
}

TEST(ray_from_inside_hits_far_side) {
    const Shape s = parse_shape("1  2  0 0 0");
    const auto hit = first_hit(s, {{0.5, 0, 0}, {1, 0, 0}});
    CHECK(hit.has_value());
    if (hit) CHECK_NEAR(hit->t, 1.5, 1e-12);
    CHECK_NEAR(s.normal({2, 0, 0}, Hit{}), Vec3(1, 0, 0), 1e-12);
}

TEST(grazing_ray_touches_once) {
    const Shape s = parse_shape("1  1  0 0 0");
    const auto hit = first_hit(s, {{-5, 1, 0}, {1, 0, 0}});
    CHECK(hit.has_value());
    if (hit) CHECK_NEAR(hit->t, 5, 1e-6);
    CHECK(!first_hit(s, {{-5, 1 + 1e-6, 0}, {1, 0, 0}}));
}

TEST(far_small_sphere_is_accurate) {
    const Shape s = parse_shape("1  0.001  0 0 -10000");
    const auto hit = first_hit(s, {{0, 0, 0}, {0, 0, -1}});
    CHECK(hit.has_value());
    if (hit) CHECK_NEAR(hit->t, 9999.999, 1e-9);
}

TEST(best_distance_so_far_stops_early) {
    const Shape s = parse_shape("1  1  0 0 -10");
    Hit hit{123, 7};
    CHECK(!s.intersect({{0, 0, 0}, {0, 0, -1}}, {1e-9, 8.5}, hit));
    CHECK_EQ(hit.t, 123.0);  // left alone on a miss
    CHECK(s.intersect({{0, 0, 0}, {0, 0, -1}}, {1e-9, 9.5}, hit));
    CHECK_NEAR(hit.t, 9, 1e-12);
}

TEST(inside_test) {
    const Shape s = parse_shape("1  2  1 1 1");
    CHECK(s.has_inside());
    CHECK(s.inside({1, 1, 1}));
    CHECK(s.inside({2.9, 1, 1}));
    CHECK(!s.inside({3.1, 1, 1}));
    CHECK(!s.inside({-1, -1, -1}));
}

TEST(bad_radius_is_an_error) {
    CHECK_CONTAINS(scene_error(std::string(kTestViewer) + "1 -1 0 0 0 100 1 1 1 0 1 1 0 1"),
                   "test.in:2:3: sphere radius must be > 0, got -1");
    CHECK_CONTAINS(scene_error(std::string(kTestViewer) + "1 0 0 0 0 100 1 1 1 0 1 1 0 1"),
                   "sphere radius must be > 0, got 0");
}

// ---- The hierarchy's cull of eight spheres at a time (accel/sphere_cull.h) ----

namespace {

// Whether the cull keeps lane `lane` of the group, asked as the portable walk asks and, where
// the processor has AVX2, as the AVX2 walk does; the two must agree.
unsigned cull_keeps(const SphereCull& cull, const Ray& ray, Interval range, std::uint32_t first,
                    std::uint32_t count) {
    const SphereCull::Ray8 r = SphereCull::prepare(ray, range.t_min);
    const unsigned portable = cull.keep<false>(r, first, count, range.t_max);
#if RT_AVX2_PATH
    if (kHasAvx2) CHECK_EQ(cull.keep<true>(r, first, count, range.t_max), portable);
#endif
    return portable;
}

}  // namespace

// The cull must never drop a sphere the exact test finds a crossing of in range: the same
// spheres, rays and range ends as above (from inside, outside, on the surface and grazing,
// at every scale from 2^-20 to 2^20, ends on the computed roots and a few doubles either
// side), some at scales down to 2^-75 and up to 2^55, each sphere in a random lane of a
// group of eight among seven others. And it must drop most of the rest, by each of its three
// rules (the floor under its bounds, kFloor, fails this test when taken away).
TEST(the_cull_never_drops_a_crossing_and_drops_most_misses) {
    Random random(78);
    int crossed = 0, dropped_miss = 0, dropped_behind = 0, dropped_beyond = 0;
    for (int i = 0; i < 20000; ++i) {
        // Now and then a scale where the floats' squares would be subnormal, or past the
        // cull's range of magnitudes (1e15), where it keeps everything.
        const int exponent = i % 11 == 0   ? static_cast<int>(random.uniform(-75, -60))
                             : i % 13 == 0 ? static_cast<int>(random.uniform(40, 55))
                                           : static_cast<int>(random.uniform(-20, 20));
        const double scale = std::ldexp(1.0, exponent);
        const double r = scale * random.uniform(0.01, 1);
        const Vec3 centre = random.in_box(scale * (i % 4 == 0 ? 1e4 : 3));
        const Vec3 direction = random.unit_vector();
        Vec3 origin = centre + random.in_box(r * (i % 3 == 0 ? 0.7 : 4));
        if (i % 5 == 0) origin = centre + random.unit_vector() * r;
        if (i % 7 == 0) {
            const Vec3 side = normalized(cross(direction, random.unit_vector()));
            origin = centre + side * (r * random.uniform(0.999999, 1.000001)) -
                     direction * (r * random.uniform(-3, 3));
        }
        const Ray ray{origin, direction};
        const SphereParameters sphere{centre, r * r};
        // The group: the sphere at `lane` of 8 places starting at `first`, the others random.
        const std::uint32_t count = 1 + static_cast<std::uint32_t>(random.next() % 8);
        const std::uint32_t lane = static_cast<std::uint32_t>(random.next() % count);
        const std::uint32_t first = static_cast<std::uint32_t>(random.next() % 3);
        SphereCull cull(first + count);
        for (std::uint32_t k = 0; k < count; ++k)
            cull.set(first + k, k == lane ? sphere
                                          : SphereParameters{random.in_box(scale * 4),
                                                             scale * random.uniform(0.01, 1)});
        const SphereQuadratic k = sphere_quadratic(sphere, ray);
        double near = 0, far = 0;
        const bool roots =
            k.discriminant >= 0 && quadratic_crossing(k, {-kInfinity, kInfinity}, near);
        if (!roots || !quadratic_crossing(k, {near, kInfinity}, far)) far = near;
        std::vector<double> ends{0, 1e-9 * scale, scale * random.uniform(0, 8), kInfinity};
        if (roots) add_ends_around(ends, near, far);
        for (const double t_min : ends) {
            for (const double t_max : ends) {
                if (!(t_min >= 0) || !(t_min <= t_max)) continue;
                double t = 0;
                const bool crosses = sphere_crossing(sphere, ray, {t_min, t_max}, t);
                const bool keeps =
                    (cull_keeps(cull, ray, {t_min, t_max}, first, count) >> lane & 1) != 0;
                if (crosses) {
                    ++crossed;
                    CHECK(keeps);
                    if (!keeps) return;  // one report is enough
                } else if (!keeps) {
                    ++(k.discriminant < 0 ? dropped_miss
                       : k.b > 0          ? dropped_behind
                                          : dropped_beyond);
                }
            }
        }
    }
    CHECK(crossed > 10000);
    CHECK(dropped_miss > 20000);
    CHECK(dropped_behind > 5000);
    CHECK(dropped_beyond > 1000);  // the whole sphere past t_max: few of these ranges
}

TEST(the_cull_keeps_what_it_cannot_judge) {
    // Places never set, spheres and origins beyond its range of magnitudes, a direction not
    // of unit length, and NaN: kept, every lane.
    SphereCull cull(8);
    cull.set(1, {{1e16, 0, 0}, 1});
    cull.set(2, {{0, 0, 10}, 1e32});
    cull.set(3, {{0, 0, 10}, 1});
    cull.set(4, {{std::nan(""), 0, 10}, 1});
    cull.set(5, {{0, 100, 10}, std::nan("")});
    const Interval all{0, kInfinity};
    CHECK_EQ(cull_keeps(cull, {{0, 0, 0}, {1, 0, 0}}, all, 0, 3), 7u);
    CHECK_EQ(cull_keeps(cull, {{0, 0, 0}, {1, 0, 0}}, all, 3, 3), 6u);       // 3 is missed
    CHECK_EQ(cull_keeps(cull, {{0, 0, 0}, {0, 0, 1}}, all, 3, 1), 1u);       // 3 is ahead
    CHECK_EQ(cull_keeps(cull, {{0, 0, 0}, {0, 0, 1}}, {0, 8.9}, 3, 1), 0u);  // beyond 8.9
    CHECK_EQ(cull_keeps(cull, {{0, 0, 0}, {0, 0, -1}}, all, 3, 1), 0u);      // behind
    CHECK_EQ(cull_keeps(cull, {{0, 0, 0}, {0, 0, -1}}, {-1, kInfinity}, 3, 1), 1u);
    CHECK_EQ(cull_keeps(cull, {{0, 0, 0}, {1, 0, 0}}, {0, -1}, 3, 1), 0u);  // missed all the same
    CHECK_EQ(cull_keeps(cull, {{0, 0, 0}, {0, 0, 2}}, all, 3, 1), 1u);      // not a unit direction
    CHECK_EQ(cull_keeps(cull, {{0, 0, 0}, {1, 0, 0}}, all, 0, 8), 0xf7u);
    CHECK_EQ(cull_keeps(cull, {{2e15, 0, 0}, {1, 0, 0}}, all, 3, 1), 1u);
    CHECK_EQ(cull_keeps(cull, {{std::nan(""), 0, 0}, {1, 0, 0}}, all, 3, 1), 1u);
}
