// The tracer against hand-computed values: the Phong terms, falloff, shadows, reflection,
// refraction, the recursion limits and the render modes.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "rt/optics.h"
#include "rt/render.h"
#include "rt/trace.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

// A 2x2 image looking down -z from (0,0,5): pixel (1,1) is the ray straight along the axis
// (pixel corners, as the original prints the formula).
const std::string kViewer2x2 = "102  0 0 5  0 0 0  1 0 0  0 1 0  2 2\n";
// A unit sphere at the origin with colour (1, 0.5, 0.25), ks 0.5, ke 10, kd 0.8, opaque.
const std::string kSphere = "1 1 0 0 0  100 1 0.5 0.25 0.5 10 0.8 0 1\n";

Spectrum centre_pixel(const std::string& scene_text, const RenderOptions& options = {}) {
    const Scene scene = parse_scene(scene_text);
    return Tracer(scene, options).pixel(1, 1);
}

}  // namespace

TEST(ambient_only) {
    const Spectrum v = centre_pixel(kViewer2x2 + kSphere + "103 0.5 0.5 0.5\n");
    // I_a kd colour, plus ks times the ambient that the reflected ray brings back.
    const double reflected = 0.5 * 0.5;
    CHECK_NEAR(v, Spectrum(0.5 * 0.8 * 1, 0.5 * 0.8 * 0.5, 0.5 * 0.8 * 0.25) + Spectrum(reflected),
               1e-12);
}

TEST(light_straight_on_without_falloff) {
    // Hit (0,0,1), normal (0,0,1); light on the axis: d.s = 1 and r.s = 1.
    const Spectrum v = centre_pixel(kViewer2x2 + kSphere + "104 0 0 10  2 2 2\n");
    CHECK_NEAR(v, Spectrum(2 * (0.8 * 1 + 0.5), 2 * (0.8 * 0.5 + 0.5), 2 * (0.8 * 0.25 + 0.5)),
               1e-12);
}

TEST(light_straight_on_with_inverse_square_falloff) {
    const Spectrum v = centre_pixel(kViewer2x2 + kSphere + "101 0 0 10  81 81 81\n");
    // Distance 9: 81 / 81 = 1.
    CHECK_NEAR(v, Spectrum(0.8 * 1 + 0.5, 0.8 * 0.5 + 0.5, 0.8 * 0.25 + 0.5), 1e-12);
}

TEST(light_at_45_degrees) {
    // From (0,0,1) the light at (0,4,5) is at distance sqrt(32) along (0,1,1)/sqrt(2):
    // d.s = r.s = 1/sqrt(2), (1/sqrt(2))^10 = 1/32, falloff 1/32.
    const Spectrum v = centre_pixel(kViewer2x2 + kSphere + "101 0 4 5  32 32 32\n");
    const double c = 1 / std::sqrt(2.0);
    CHECK_NEAR(v[0], 0.8 * 1 * c + 0.5 / 32, 1e-12);
    CHECK_NEAR(v[1], 0.8 * 0.5 * c + 0.5 / 32, 1e-12);
    CHECK_NEAR(v[2], 0.8 * 0.25 * c + 0.5 / 32, 1e-12);
}

TEST(light_behind_the_surface_adds_nothing) {
    const Spectrum v = centre_pixel(kViewer2x2 + kSphere + "104 0 0 -10  1 1 1\n");
    CHECK_NEAR(v, Spectrum(0.0), 0);
}

TEST(shadow_blocks_light_but_not_ambient) {
    const std::string scene = kViewer2x2 + kSphere + "104 0 0 10  1 1 1\n103 0.5 0.5 0.5\n" +
                              "1 0.1  0 0 6  100 1 1 1 0 1 1 0 1\n";  // a blocker on the axis
    // The blocker is also seen by the primary ray, so look at the sphere through a pixel
    // beside it: use the tracer directly with a ray that misses the blocker.
    const Scene s = parse_scene(scene);
    RenderOptions options;
    Tracer tracer(s, options);
    const Ray ray{{0, 0, 3}, {0, 0, -1}};  // starts past the blocker
    // The mirror term sees the blocker's unlit underside: ks 0.5 x ambient 0.5 x kd 1.
    const Spectrum mirror(0.25);
    CHECK_NEAR(tracer.trace(ray), Spectrum(0.4, 0.2, 0.1) + mirror, 1e-12);  // ambient only
    options.shadows = false;
    CHECK_NEAR(Tracer(s, options).trace(ray), Spectrum(0.4 + 1.3, 0.2 + 0.9, 0.1 + 0.7) + mirror,
               1e-12);
}

// A light whose term at a point of a surface without a diffuse term is exactly zero (no
// highlight, or one too sharp to show) needs no shadow ray there; one that adds anything,
// and any light on a diffuse surface, still asks.
TEST(a_light_that_adds_nothing_casts_no_shadow_ray) {
    RenderOptions options;
    options.reflection = false;
    const auto shade = [&](const std::string& sphere, const std::string& lights) {
        const Scene scene = parse_scene(kViewer2x2 + sphere + lights);
        Tracer tracer(scene, options);
        const Spectrum v = tracer.pixel(1, 1);
        return std::pair{v, tracer.stats().shadow_rays};
    };
    const std::string white_light = "104 0 0 10  2 2 2\n";
    // No diffuse term and no highlight: black, and no shadow ray.
    auto [v, shadow] = shade("1 1 0 0 0  100 1 1 1 0 10 0 0 1\n", white_light);
    CHECK_NEAR(v, Spectrum(0.0), 0);
    CHECK_EQ(shadow, 0u);
    // A highlight only, straight on: 2 x ks, and the shadow ray is cast.
    std::tie(v, shadow) = shade("1 1 0 0 0  100 1 1 1 0.5 10 0 0 1\n", white_light);
    CHECK_NEAR(v, Spectrum(1.0), 1e-12);
    CHECK_EQ(shadow, 1u);
    // The same highlight at 45 degrees with exponent 1e5: (1/sqrt 2)^1e5 is 0 in a double.
    std::tie(v, shadow) = shade("1 1 0 0 0  100 1 1 1 0.5 1e5 0 0 1\n", "104 0 4 5  2 2 2\n");
    CHECK_NEAR(v, Spectrum(0.0), 0);
    CHECK_EQ(shadow, 0u);
    // A diffuse surface always asks: a red light on a cyan one adds nothing without a
    // highlight, but only a surface without a diffuse term is spared the shadow ray...
    const std::string red_light = "104 0 0 10  2 0 0\n";
    std::tie(v, shadow) = shade("1 1 0 0 0  100 0 1 1 0 10 0.8 0 1\n", red_light);
    CHECK_NEAR(v, Spectrum(0.0), 0);
    CHECK_EQ(shadow, 1u);
    // ...and with a highlight the red shows (2 x 0.5).
    std::tie(v, shadow) = shade("1 1 0 0 0  100 0 1 1 0.5 10 0.8 0 1\n", red_light);
    CHECK_NEAR(v, Spectrum(1.0, 0, 0), 1e-12);
    CHECK_EQ(shadow, 1u);
    // A black surface with a highlight of exponent 1e5 straight on: 2 x ks, after the ray.
    std::tie(v, shadow) = shade("1 1 0 0 0  100 0 0 0 0.5 1e5 0.8 0 1\n", white_light);
    CHECK_NEAR(v, Spectrum(1.0), 1e-12);
    CHECK_EQ(shadow, 1u);
    // A highlight behind a blocker: the ray is cast, and the light adds nothing.
    {
        const Scene scene = parse_scene(kViewer2x2 + "1 1 0 0 0  100 1 1 1 0.5 10 0 0 1\n" +
                                        white_light + "1 0.1  0 0 6  100 1 1 1 0 1 1 0 1\n");
        Tracer tracer(scene, options);
        CHECK_NEAR(tracer.trace({{0, 0, 3}, {0, 0, -1}}), Spectrum(0.0), 0);
        CHECK_EQ(tracer.stats().shadow_rays, 1u);
    }
    // A diffuse term alone lights the point and asks once; the light behind asks nothing.
    std::tie(v, shadow) = shade(kSphere, "104 0 0 -10  1 1 1\n104 0 0 10  1 1 1\n");
    CHECK_NEAR(v, Spectrum(0.8 + 0.5, 0.4 + 0.5, 0.2 + 0.5), 1e-12);
    CHECK_EQ(shadow, 1u);
}

// Each level of the ray tree keeps its own last blocker per light (Tracer::blockers_at).
// Two floor points shadowed by two different spheres: traced in turns at one level, each
// shadow ray first asks the other point's blocker in vain; at two levels, each finds its own,
// and the turns cost exactly the tests that tracing each point's rays together costs. The
// answers (shadowed, ambient only) never depend on the order.
TEST(each_level_of_the_ray_tree_keeps_its_own_last_blocker) {
    const std::string white = "  100 1 1 1 0 1 1 0 1\n";
    const Scene scene =
        parse_scene(kViewer2x2 + "2 0  0 1 0" + white + "1 1  -5 3 0" + white + "1 1  5 3 0" +
                    white + "104 0 1000 0  1 1 1\n" + "103 0.5 0.5 0.5\n");
    const Ray under_a{{-5, 1.5, 0}, {0, -1, 0}};  // below sphere A, down to the floor
    const Ray under_b{{5, 1.5, 0}, {0, -1, 0}};
    constexpr int kRays = 10;
    const auto tests = [&](int depth_a, int depth_b, bool in_turns) {
        Tracer tracer(scene, RenderOptions{});
        for (int i = 0; i < 2 * kRays; ++i) {
            const bool a = in_turns ? i % 2 == 0 : i < kRays;
            const Spectrum v = a ? tracer.trace(under_a, depth_a) : tracer.trace(under_b, depth_b);
            CHECK_NEAR(v, Spectrum(0.5), 0);  // ambient 0.5 x kd 1 x white: in shadow
        }
        CHECK_EQ(tracer.stats().shadow_rays, std::uint64_t{2 * kRays});
        return tracer.stats().object_tests;
    };
    // One level: every turn but the first asks the other point's blocker first, in vain (and
    // then the floor and the hierarchy, which a blocker found first spares).
    CHECK(tests(0, 0, true) >= tests(0, 0, false) + 2 * kRays - 2);
    // Two levels, and the levels past the last row shared (kBlockerLevels): no test more.
    CHECK_EQ(tests(0, 1, true), tests(0, 1, false));
    CHECK_EQ(tests(2, 5, true), tests(2, 5, false));
    CHECK(tests(7, 9, true) > tests(7, 9, false));
}

// With four lights or more the point lights are sampled before the loop over the lights
// (Tracer::kBatchFrom); the terms must be those of the lights one at a time, added in the
// scene's order. Nine lights of every kind (one more than the batch holds, so the last is
// sampled in the loop; one sample each, since a light's own samples are added together
// first), some shadowed by a small sphere, at points all over a sphere and a floor: each
// pixel is compared with the sum, in order, of the same pixel lit by each light alone, to
// the bit. Taking one light's batched sample for another's fails it.
TEST(many_lights_sum_as_each_light_alone_in_order) {
    const std::string viewer = "102  0 1 6  0 0.5 0  1 0 0  0 1 0  24 24\n";
    const std::string objects =
        "1 1  0 0.6 0  100 0.9 0.6 0.3 0.4 20 0.7 0 1\n"
        "1 0.15  -0.9 1.9 0.4  100 0.2 0.8 0.4 0.3 5 0.9 0 1\n"
        "2 0  0 1 0  100 0.7 0.7 0.7 0.2 8 0.8 0 1\n";
    const std::vector<std::string> lights = {
        "101  -3 4 2  9 8 7\n",
        "104  2 3 4  0.3 0.2 0.1\n",
        "113  0.3 -1 -0.2  0.2 0.25 0.3\n",
        "104  -2 5 -1  0.1 0.3 0.2\n",
        "109  1 4 3  -0.2 -1 -0.6  0.8 4  6 6 6\n",
        "101  4 2 -3  5 5 8\n",
        "110  1  -4 3 3  0.5  4 4 4\n",
        "104  0 6 0  0.2 0.2 0.2\n",
        "101  -1.5 3.5 1.5  3 2 1\n",
    };
    std::string all;
    for (const std::string& light : lights) all += light;
    RenderOptions options;
    options.ambient = false;  // a pixel is then its lights' sum alone
    options.max_depth = 0;    // and no reflection adds to it
    const Scene scene = parse_scene(viewer + objects + all);
    std::vector<Scene> alone;
    for (const std::string& light : lights) alone.push_back(parse_scene(viewer + objects + light));
    Tracer tracer(scene, options);
    int lit = 0;
    for (int y = 0; y < 24; ++y) {
        for (int x = 0; x < 24; ++x) {
            Spectrum sum(0.0);
            for (const Scene& one : alone) sum += Tracer(one, options).pixel(x, y);
            const Spectrum value = tracer.pixel(x, y);
            CHECK(value == sum);
            lit += !value.is_black();
        }
    }
    CHECK(lit > 24 * 24 / 2);
}

TEST(switches_remove_their_terms) {
    const std::string scene = kViewer2x2 + kSphere + "104 0 0 10  1 1 1\n103 0.5 0.5 0.5\n";
    RenderOptions options;
    options.reflection = false;  // so the escaping mirror ray adds no ambient
    CHECK_NEAR(centre_pixel(scene, options), Spectrum(1.7, 1.1, 0.8), 1e-12);
    options.ambient = false;
    CHECK_NEAR(centre_pixel(scene, options), Spectrum(1.3, 0.9, 0.7), 1e-12);
    options.diffuse = false;
    CHECK_NEAR(centre_pixel(scene, options), Spectrum(0.5), 1e-12);
    options.specular = false;
    CHECK_NEAR(centre_pixel(scene, options), Spectrum(0.0), 0);
}

TEST(escaping_rays_bring_back_ambient) {
    const Scene scene = parse_scene(kViewer2x2 + "103 0.1 0.2 0.3\n");
    CHECK_NEAR(Tracer(scene, {}).pixel(0, 0), Spectrum(0.1, 0.2, 0.3), 0);
    CHECK_NEAR(Tracer(parse_scene(kViewer2x2), {}).pixel(0, 0), Spectrum(0.0), 0);
}

TEST(mirror_reflection_and_depth_limit) {
    // A mirror plane z = 0 (ks 0.5, kd 0) facing the eye, and behind the eye a white plane
    // lit only by ambient 1: the mirror shows 0.5 x (the white plane's 1 x kd 0.6).
    const std::string scene = kViewer2x2 + "103 1 1 1\n" + "2 0  0 0 1  100 1 1 1 0.5 1 0 0 1\n" +
                              "2 10 0 0 1  100 1 1 1 0 1 0.6 0 1\n";
    CHECK_NEAR(centre_pixel(scene), Spectrum(0.5 * 0.6), 1e-12);
    RenderOptions options;
    options.max_depth = 0;  // no secondary rays at all
    CHECK_NEAR(centre_pixel(scene, options), Spectrum(0.0), 0);
    options.max_depth = 7;
    options.min_weight = 0.6;  // the reflected ray's weight 0.5 is below the cut-off
    CHECK_NEAR(centre_pixel(scene, options), Spectrum(0.0), 0);
    options.min_weight = 0.5;  // not below: traced
    CHECK_NEAR(centre_pixel(scene, options), Spectrum(0.3), 1e-12);
    options = {};
    options.reflection = false;
    CHECK_NEAR(centre_pixel(scene, options), Spectrum(0.0), 0);
}

TEST(parallel_mirrors_stop_at_the_depth_limit) {
    // Two facing mirrors that reflect everything: each bounce adds ambient 1 x kd 0.1 x 0.9^k.
    const std::string scene = kViewer2x2 + "103 1 1 1\n" + "2 0  0 0 1  100 1 1 1 0.9 1 0.1 0 1\n" +
                              "2 10 0 0 1  100 1 1 1 0.9 1 0.1 0 1\n";
    for (int depth : {0, 1, 3, 7}) {
        RenderOptions options;
        options.max_depth = depth;
        options.min_weight = 0;
        double expected = 0;
        for (int k = 0; k <= depth; ++k) expected += 0.1 * std::pow(0.9, k);
        CHECK_NEAR(centre_pixel(scene, options)[0], expected, 1e-12);
    }
}

TEST(reflect_obeys_the_law_of_reflection) {
    Random random(7);
    for (int i = 0; i < 10000; ++i) {
        const Vec3 n = random.unit_vector();
        Vec3 in = random.unit_vector();
        if (dot(in, n) > 0) in = -in;
        const Vec3 r = reflect(in, n);
        CHECK_NEAR(length(r), 1, 1e-12);
        CHECK_NEAR(dot(r, n), -dot(in, n), 1e-12);   // equal angles
        CHECK_NEAR(dot(cross(in, n), r), 0, 1e-12);  // in the plane of incidence
        CHECK_NEAR(length(cross(in, n)), length(cross(r, n)), 1e-12);
    }
}

TEST(a_highlight_judged_too_small_leaves_every_sum_as_it_is) {
    // The tracer skips pow where highlight_may_count says the highlight cannot change the
    // sum it joins. Checked here on the sums themselves: the highlight as the tracer computes
    // it, added to terms from the smallest up to 2^30 times it, must leave each bit for bit.
    // The angles are chosen so that the bound lands within 20 of its threshold either side,
    // where a threshold a few units too low would let a highlight through.
    constexpr double kLog2E = 1.4426950408889634;
    Random random(41);
    int skipped = 0, counted_and_changing = 0;
    for (int i = 0; i < 200000; ++i) {
        const int smallest_exp = static_cast<int>(random.uniform(-40, 10));
        const int ks_exp = static_cast<int>(random.uniform(-20, 5));
        const double smallest = std::ldexp(random.uniform(1, 2), smallest_exp);
        const double ks = std::ldexp(random.uniform(1, 2), ks_exp);
        const double ke = i % 4 == 0 ? random.uniform(1, 30) : std::exp(random.uniform(0, 11.6));
        const double fall = ks_exp - smallest_exp + 56 + random.uniform(-20, 20);
        double c = 1 - fall / (ke * kLog2E);
        if (!(c > 0 && c < 1)) c = random.uniform();
        if (!(c > 0)) continue;
        const double highlight = ks * std::pow(c, ke);
        bool changes = false;
        const bool may_count = highlight_may_count(smallest, ks, c, ke);
        for (int k = 0; k < 4; ++k) {
            const double term = k == 0 ? smallest : smallest * std::ldexp(random.uniform(1, 2), k * 10);
            const bool same = term + highlight == term;
            if (!same) changes = true;
            if (!may_count) CHECK(same);
        }
        if (!may_count) ++skipped;
        if (may_count && changes) ++counted_and_changing;
    }
    // Both sides are exercised: many skipped, and many that were rightly computed.
    CHECK(skipped > 50000);
    CHECK(counted_and_changing > 50000);
    // A few worked values: exponent 200 at cos 0.5 falls about 200 binary places; at 0.99,
    // about 2.9.
    CHECK(!highlight_may_count(0.3, 0.15, 0.5, 200));
    CHECK(highlight_may_count(0.3, 0.15, 0.99, 200));
    // What it cannot judge, it counts.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    for (const auto& [smallest, ks, c, ke] : std::vector<std::tuple<double, double, double, double>>{
             {0, 1, 0.1, 1e5}, {1e-300, 1, 0.1, 1e5}, {inf, 1, 0.1, 1e5}, {nan, 1, 0.1, 1e5},
             {1, nan, 0.1, 1e5}, {1, inf, 0.1, 1e5}, {1, 1, nan, 1e5}, {1, 1, 1, 1e5},
             {1, 1, 1.5, 1e5}, {1, 1, 0.1, 0}, {1, 1, 0.1, -5}, {1, 1, 0.1, nan}})
        CHECK(highlight_may_count(smallest, ks, c, ke));
    CHECK(!highlight_may_count(1, 1, 0.1, inf));  // pow gives 0
}

TEST(refract_obeys_snells_law) {
    Random random(11);
    int total_internal = 0;
    for (int i = 0; i < 10000; ++i) {
        const Vec3 n = random.unit_vector();
        Vec3 in = random.unit_vector();
        if (dot(in, n) > 0) in = -in;
        const double n1 = random.uniform(1, 2.5), n2 = random.uniform(1, 2.5);
        const double sin_i = length(cross(in, n));
        const auto t = refract(in, n, n1 / n2);
        if (n1 / n2 * sin_i > 1 + 1e-12) {
            CHECK(!t);
            ++total_internal;
            continue;
        }
        if (n1 / n2 * sin_i > 1 - 1e-12) continue;  // at the critical angle either is right
        CHECK(t.has_value());
        if (!t) continue;
        CHECK_NEAR(length(*t), 1, 1e-12);
        CHECK(dot(*t, n) < 0);                                    // goes through the surface
        CHECK_NEAR(n1 * sin_i, n2 * length(cross(*t, n)), 1e-9);  // Snell's law
        CHECK_NEAR(dot(cross(in, n), *t), 0, 1e-12);              // in the plane of incidence
    }
    CHECK(total_internal > 100);
}

TEST(glass_sphere_bends_the_ray_as_the_index_bookkeeping_says) {
    // A ray parallel to the axis at height h enters a glass sphere (index 1.5), crosses it and
    // leaves. Work out the exit ray in 2-D by hand, put a small red disk where it lands on a
    // screen at z = -10, and see the disk through the sphere. A ray that kept index 1.5 on
    // leaving, or that never bent, lands elsewhere and shows the blue screen.
    const double h = 0.5, n = 1.5;
    const double theta1 = std::asin(h);              // incidence on entry
    const double theta2 = std::asin(h / n);          // refraction inside
    const double deviation = 2 * (theta1 - theta2);  // total turn after entry and exit
    // Exit point: the chord inside turns by pi - 2 theta2 around the centre.
    const double entry_angle = theta1;  // polar angle of the entry point, from +z toward +y
    const double exit_angle = entry_angle + (std::numbers::pi - 2 * theta2);
    const Vec3 exit{0, std::sin(exit_angle), std::cos(exit_angle)};
    const Vec3 direction{0, -std::sin(deviation), -std::cos(deviation)};
    const double t_screen = (-10 - exit.z) / direction.z;
    const Vec3 spot = exit + t_screen * direction;

    const std::string scene = std::string(kViewer2x2) + "103 1 1 1\n" +
                              "1 1 0 0 0  100 1 1 1 0 1 0 1 1.5\n" +
                              object_text(3, {spot.x, spot.y, spot.z, 0, 0, 1, 0.05}) +
                              " 100 1 0 0 0 1 1 0 1\n" + "2 -10.001 0 0 1  100 0 0 1 0 1 1 0 1\n";
    const Scene s = parse_scene(scene);
    Tracer tracer(s, {});
    CHECK_NEAR(tracer.trace({{0, h, 5}, {0, 0, -1}}), Spectrum(1.0, 0.0, 0.0), 1e-12);
    // A ray through the centre is not bent at all and sees the screen.
    CHECK_NEAR(tracer.trace({{0, 0, 5}, {0, 0, -1}}), Spectrum(0.0, 0.0, 1.0), 1e-12);
}

TEST(total_internal_reflection_moves_kt_to_reflection) {
    // Inside a glass sphere (index 1.5) a ray meeting the surface beyond the critical angle
    // (41.8 degrees) is reflected with weight ks + kt, and inside a sphere it meets the
    // surface at the same angle every time, so it never escapes: nothing comes back. Below
    // the critical angle it leaves and brings back the ambient light.
    const std::string scene =
        std::string(kViewer2x2) + "103 1 1 1\n" + "1 1 0 0 0  100 1 1 1 0 1 0 1 1.5\n";
    const Scene s = parse_scene(scene);
    RenderOptions options;
    options.min_weight = 0;
    Tracer tracer(s, options);
    const auto from_inside = [&](double angle_degrees) {
        // From the centre offset so that the ray hits the surface at the given angle.
        const double a = angle_degrees * std::numbers::pi / 180;
        const Vec3 origin{0, std::sin(a), 0};
        return tracer.trace({origin, {1, 0, 0}}, 0, 1, 1.5);
    };
    CHECK_NEAR(from_inside(30), Spectrum(1.0), 1e-12);  // leaves: kt x ambient
    CHECK_NEAR(from_inside(60), Spectrum(0.0), 1e-12);  // trapped until the depth limit
    // With refraction off there is no transmission and so no total internal reflection.
    options.refraction = false;
    CHECK_NEAR(Tracer(s, options).trace({{0, 0.8, 0}, {1, 0, 0}}, 0, 1, 1.5), Spectrum(0.0), 0);
}

TEST(render_modes) {
    const std::string scene = kViewer2x2 + kSphere + "104 0 0 10  1 1 1\n";
    const Scene s = parse_scene(scene);
    RenderOptions options;
    options.mode = RenderMode::depth;
    CHECK_NEAR(Tracer(s, options).pixel(1, 1), Spectrum(0.25), 1e-12);  // hit at distance 4
    CHECK_NEAR(Tracer(s, options).pixel(0, 0), Spectrum(0.0), 0);       // misses: black
    options.mode = RenderMode::colour;
    CHECK_NEAR(Tracer(s, options).pixel(1, 1), Spectrum(1.0, 0.5, 0.25), 0);
    options.mode = RenderMode::normal;
    CHECK_NEAR(Tracer(s, options).pixel(1, 1), Spectrum(1.0), 1e-12);
    // Depth is capped at 1 for hits nearer than one unit.
    const Scene near = parse_scene("102 0 0 1.5 0 0 0 1 0 0 0 1 0 2 2\n" + kSphere);
    options.mode = RenderMode::depth;
    CHECK_NEAR(Tracer(near, options).pixel(1, 1), Spectrum(1.0), 0);
}

TEST(normal_mode_off_axis) {
    // Pixel (1, 0) of a 2x2 image with y = (0, 0.1, 0) looks through (0, 0.1, 4) from
    // (0, 0, 5); it meets the unit sphere at p, where the normal is p itself.
    const Scene s = parse_scene("102  0 0 5  0 0 0  0.1 0 0  0 0.1 0  2 2\n" + kSphere);
    RenderOptions options;
    options.mode = RenderMode::normal;
    const Vec3 o{0, 0, 5}, d = normalized(Vec3(0, 0.1, -1));
    const double b = dot(o, d), t = -b - std::sqrt(b * b - (dot(o, o) - 1));
    const Vec3 p = o + t * d;
    CHECK_NEAR(Tracer(s, options).pixel(1, 0), Spectrum(std::fabs(dot(p, d))), 1e-12);
}

TEST(camera_rays_follow_the_pixel_corner_formula) {
    // Non-perpendicular x and y vectors, as the original allows.
    Viewer v;
    v.eye = {1, 2, 3};
    v.look_at = {1, 2, -7};
    v.x = {2, 0.5, 0};
    v.y = {0.3, 1, 0.2};
    v.xres = 10;
    v.yres = 4;
    const Vec3 centre = v.eye + Vec3(0, 0, -1);
    const Ray r = v.primary_ray(7, 1);
    const double alpha = (2.0 * 7 - 10) / 10, beta = -(2.0 * 1 - 4) / 4;
    CHECK_NEAR(r.origin, v.eye, 0);
    CHECK_NEAR(r.direction, normalized(centre + alpha * v.x + beta * v.y - v.eye), 1e-15);
}

TEST(a_rows_rays_are_the_pixels_rays_to_the_bit) {
    // row_rays takes each column's alpha from a table made once; every ray it makes must
    // still be primary_ray's, bit for bit, at sizes that are and are not powers of two. It
    // makes none for a pixel the primary mask spares in a scene without unbounded objects
    // (a small sphere leaves most of these images to the background), whose ray must then
    // meet nothing.
    static_assert(sizeof(Ray) == 6 * sizeof(double));  // no padding for memcmp to read
    for (const bool with_plane : {false, true})
        for (const auto& [w, h] :
             std::vector<std::pair<int, int>>{{37, 23}, {64, 64}, {1000, 3}, {7, 1}}) {
            Scene s = parse_scene("102 0.1 -0.2 4 0 0 0 0.5 0.02 0 0 0.5 0.05 " +
                                  std::to_string(w) + " " + std::to_string(h) +
                                  "\n1 0.7  0.3 0.1 0  100 1 0.5 0.25 0.5 10 0.8 0 1\n" +
                                  (with_plane ? "2  0 1 0 8  100 1 1 1 0.5 10 0.8 0 1\n" : ""));
            const Tracer tracer(s, RenderOptions{});
            RenderOptions scan_options;
            scan_options.accelerate = false;
            Tracer scan(s, scan_options);  // the linear scan, to judge what a ray meets
            std::vector<Ray> rays;
            std::vector<unsigned char> spared;
            std::size_t spared_in_all = 0;
            for (int y = 0; y < h; ++y)
                for (const auto& [x0, x1] : std::vector<std::pair<int, int>>{{0, w}, {w / 3, w - w / 4}}) {
                    const std::size_t count = tracer.row_rays(y, x0, x1, rays, spared);
                    CHECK_EQ(rays.size(), static_cast<std::size_t>(x1 - x0));
                    CHECK_EQ(spared.size(), rays.size());
                    std::size_t marked = 0;
                    for (int x = x0; x < x1; ++x) {
                        const auto i = static_cast<std::size_t>(x - x0);
                        marked += spared[i];
                        if (spared[i] != 0) {
                            CHECK(!with_plane);
                            CHECK(!scan.closest_hit(tracer.primary_ray(x, y)).has_value());
                            continue;
                        }
                        const Ray expected = tracer.primary_ray(x, y);
                        CHECK(std::memcmp(&rays[i], &expected, sizeof(Ray)) == 0);
                    }
                    CHECK_EQ(count, marked);
                    if (x0 == 0) spared_in_all += count;
                }
            if (!with_plane && w == h) CHECK(spared_in_all > static_cast<std::size_t>(w * h / 2));
            if (!with_plane && w >= 37) CHECK(spared_in_all > 0);
            if (with_plane) CHECK_EQ(spared_in_all, 0u);
        }
}

// The render makes a row's rays before tracing them (Tracer::row_rays); every pixel must
// still be exactly the tracer's pixel(), as for a region and with supersampling.
TEST(render_is_the_tracers_pixel_for_every_pixel) {
    const Scene s = parse_scene("102 0.3 -0.2 5 0 0 0 1.3 0.1 0 0 0.9 0.2 37 23\n" + kSphere +
                                "1 0.4  1 1 1.5  100 0.2 0.9 0.3 0.6 20 0.5 0 1\n"
                                "101 2 3 4 20 20 20\n103 .1 .1 .1\n");
    for (int samples : {1, 2}) {
        RenderOptions options;
        options.threads = 2;
        options.samples = samples;
        const Raster image = render(s, options);
        Tracer tracer(s, options);
        bool same = true;
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x)
                same = same && image.at(x, y) == tracer.pixel(x, y);
        CHECK(same);
        CHECK(tracer.primary_ray(5, 7).direction == s.viewer.primary_ray(5, 7).direction);
    }
}

TEST(render_is_the_same_on_any_number_of_threads) {
    const Scene s = parse_scene("102 0 0 5 0 0 0 1 0 0 0 1 0 37 23\n" + kSphere +
                                "101 2 3 4 20 20 20\n103 .1 .1 .1\n");
    RenderOptions one;
    one.threads = 1;
    const Raster a = render(s, one);
    for (int threads : {2, 3, 8}) {
        RenderOptions many;
        many.threads = threads;
        const Raster b = render(s, many);
        bool same = true;
        for (int y = 0; y < a.height(); ++y)
            for (int x = 0; x < a.width(); ++x) same = same && a.at(x, y) == b.at(x, y);
        CHECK(same);
    }
}

TEST(supersampling_averages_a_grid_centred_on_the_original_ray) {
    // Colour mode, pixel (1, 1): sample (u, v) looks through (u, -v, 4), so it meets the plane
    // z = 0 at (5u, -5v, 0). A red strip covers x >= 1 and a green square |x|, |y| <= 0.5.
    // On the centred 3 x 3 grid (u, v in {-1/3, 0, 1/3}) the column u = 1/3 is red and only
    // the middle sample, the original's ray, is green: (3/9, 1/9, 0). A grid from the corner
    // (u, v in {0, 1/3, 2/3}) would give (6/9, 1/9, 0).
    const Scene s = parse_scene(kViewer2x2 + "6  1 -10 0  9 0 0  0 20 0  100 1 0 0 0 1 1 0 1\n" +
                                "6  -0.5 -0.5 0  1 0 0  0 1 0  100 0 1 0 0 1 1 0 1\n");
    RenderOptions options;
    options.mode = RenderMode::colour;
    options.samples = 3;
    CHECK_NEAR(Tracer(s, options).pixel(1, 1), Spectrum(3.0 / 9, 1.0 / 9, 0), 1e-15);
    options.samples = 1;  // one sample is the original's ray itself
    CHECK_NEAR(Tracer(s, options).pixel(1, 1), Spectrum(0, 1, 0), 0);
}

TEST(a_supersampled_pixel_is_its_grids_mean_to_the_bit) {
    // pixel() makes its grid's rays from n alphas and n betas before tracing any; each must
    // still be primary_ray(x + u, y + v)'s, traced as shade_primary traces it, summed in
    // the grid's order. Checked bit for bit against that sum, with and without a plane (no
    // pixel is then spared), with the centre's value handed in for odd n.
    for (const bool with_plane : {false, true}) {
        const Scene s = parse_scene(
            "102 0.3 -0.2 5 0 0 0 1.3 0.1 0 0 0.9 0.2 13 9\n" + kSphere +
            "1 0.4  1 1 1.5  100 0.2 0.9 0.3 0.6 20 0.5 0 1\n101 2 3 4 20 20 20\n103 .1 .1 .1\n" +
            (with_plane ? "2  0 1 0 -1.2  100 0.7 0.7 0.7 0.5 10 0.3 0 1\n" : ""));
        Tracer oracle(s, RenderOptions{});
        for (const int n : {2, 3, 4, 7}) {
            RenderOptions options;
            options.samples = n;
            Tracer tracer(s, options);
            for (int y = 0; y < s.viewer.yres; ++y)
                for (int x = 0; x < s.viewer.xres; ++x) {
                    Spectrum sum(0.0);
                    for (int j = 0; j < n; ++j)
                        for (int i = 0; i < n; ++i) {
                            const double u = (i + 0.5) / n - 0.5, v = (j + 0.5) / n - 0.5;
                            sum += oracle.shade_primary(s.viewer.primary_ray(x + u, y + v));
                        }
                    const Spectrum expected = sum * (1.0 / (n * n));
                    const Spectrum got = tracer.pixel(x, y);
                    for (std::size_t c = 0; c < kSpectrumComponents; ++c)
                        CHECK_EQ(std::bit_cast<std::uint64_t>(got[c]),
                                 std::bit_cast<std::uint64_t>(expected[c]));
                    if (n % 2 == 1) {
                        const Spectrum centre = oracle.shade_primary(s.viewer.primary_ray(x, y));
                        const Spectrum handed = tracer.pixel(x, y, &centre);
                        for (std::size_t c = 0; c < kSpectrumComponents; ++c)
                            CHECK_EQ(std::bit_cast<std::uint64_t>(handed[c]),
                                     std::bit_cast<std::uint64_t>(expected[c]));
                    }
                }
        }
    }
}

TEST(supersampling_sums_the_expected_rays) {
    // A narrow view, so that the sphere's edge crosses pixel (0, 1).
    const Scene s =
        parse_scene("102  0 0 5  0 0 0  0.3 0 0  0 0.3 0  2 2\n" + kSphere + "104 0 0 10  1 1 1\n");
    for (int n : {1, 2, 3, 4}) {
        RenderOptions options;
        options.samples = n;
        Tracer tracer(s, options);
        options.samples = 1;
        Tracer reference(s, options);
        Spectrum sum(0.0);
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                sum += reference.shade_primary(
                    s.viewer.primary_ray(0 + (i + 0.5) / n - 0.5, 1 + (j + 0.5) / n - 0.5));
        CHECK_NEAR(tracer.pixel(0, 1), sum * (1.0 / (n * n)), 1e-15);
        // A centre value already traced replaces the middle sample without changing the sum.
        const Spectrum centre = reference.shade_primary(s.viewer.primary_ray(0, 1));
        CHECK(tracer.pixel(0, 1, &centre) == tracer.pixel(0, 1));
    }
}

TEST(supersampling_does_not_move_the_image) {
    // A small white disk facing the eye, off the axis, on black, in colour mode. Its image is a
    // circle of radius 3.3 pixels centred on raster point (24, 22) (alpha = 2/10, beta = -1/10),
    // and every centred grid samples it symmetrically about that point, so the centroid stays
    // there whatever the number of samples. A grid from the pixel corner moved it by
    // (n - 1) / 2n pixel: 1/4 for n = 2, 1/3 for n = 3.
    const Scene s = parse_scene(
        "102  0 0 10  0 0 0  1 0 0  0 1 0  40 40\n"
        "3  2 -1 0  0 0 1  1.65  100 1 1 1 0 1 1 0 1\n");
    const auto centroid = [&](int n) {
        RenderOptions options;
        options.mode = RenderMode::colour;
        options.samples = n;
        const Raster image = render(s, options);
        double sum = 0, sx = 0, sy = 0;
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x) {
                const double w = image.at(x, y)[0];
                sum += w;
                sx += w * x;
                sy += w * y;
            }
        return Vec3(sx / sum, sy / sum, 0);
    };
    for (int n : {1, 2, 3, 4}) CHECK_NEAR(centroid(n), Vec3(24, 22, 0), 1e-9);
}
