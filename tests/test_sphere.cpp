// Sphere (ID 1) against the closed form: the geometric solution of the ray-sphere problem.
#include <cmath>

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
