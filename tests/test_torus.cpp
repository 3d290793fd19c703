// Torus (ID 10) against an independent check: the signed distance to the tube,
//   g(p) = |p - nearest point of the core circle| - r,
// which vanishes exactly on the surface and is never larger in size than the distance to it
// (it is exact outside, and a lower bound inside where the tube overlaps itself), so
// stepping along the ray by |g| can never step over the surface. The test walks each ray
// that way, looking for the first sign change of g, and bisects it: the distance the torus
// reports must match. A miss must show no sign change at all.
#include <cmath>
#include <iostream>
#include <optional>

#include "rt/optics.h"
#include "rt/render.h"
#include "rt/trace.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

struct TorusSpec {
    Vec3 centre;
    Vec3 axis;  // unit
    double major, minor;

    double reach() const { return major + minor; }
    Shape shape() const {
        return parse_shape(
            object_text(10, {centre.x, centre.y, centre.z, axis.x, axis.y, axis.z, major, minor}));
    }
    // The nearest point of the core circle to p (any point of it when p is on the axis).
    Vec3 core_point(const Vec3& p) const {
        const Vec3 rel = p - centre;
        Vec3 radial = rel - dot(rel, axis) * axis;
        if (length(radial) == 0)
            radial = std::fabs(axis.x) < 0.9 ? cross(axis, {1, 0, 0}) : cross(axis, {0, 1, 0});
        return centre + normalized(radial) * major;
    }
    double g(const Vec3& p) const { return length(p - core_point(p)) - minor; }
};

// The first sign change of g along the ray in (t0, t1), bisected to rounding level. Steps
// are |g| (safe), but never shorter than min_step: a dip below the surface shorter than
// that can be stepped over, so the torus may report it or not.
std::optional<double> first_crossing(const TorusSpec& s, const Ray& ray, double t0, double t1) {
    const double min_step = 1e-5 * s.minor;
    double t = t0;
    double v = s.g(ray.at(t));
    const bool start_inside = v < 0;
    for (int i = 0; i < 2000000 && t < t1; ++i) {
        const double next = t + std::max(std::fabs(v), min_step);
        const double next_v = s.g(ray.at(next));
        if ((next_v < 0) != start_inside) {
            double lo = t, hi = next;
            for (int k = 0; k < 200 && lo < hi; ++k) {
                const double mid = 0.5 * (lo + hi);
                if (mid <= lo || mid >= hi) break;
                ((s.g(ray.at(mid)) < 0) != start_inside ? hi : lo) = mid;
            }
            return hi < t1 ? std::optional<double>(hi) : std::nullopt;
        }
        t = next;
        v = next_v;
    }
    return std::nullopt;
}

TorusSpec random_torus(Random& random) {
    const double major = std::pow(10.0, random.uniform(-1, 1));
    // Mostly ring tori, some spindle tori (minor > major).
    const double ratio =
        random.uniform() < 0.85 ? random.uniform(0.02, 0.95) : random.uniform(1, 2);
    return {random.in_box(3), random.unit_vector(), major, major * ratio};
}

// A random point of the surface (angle round the core, angle round the tube).
Vec3 surface_point(const TorusSpec& s, Random& random, double tube_fraction = 1) {
    const Vec3 u =
        normalized(cross(s.axis, std::fabs(s.axis.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
    const Vec3 v = cross(s.axis, u);
    const double phi = random.uniform(0, 6.283185307179586);
    const double theta = random.uniform(0, 6.283185307179586);
    const Vec3 radial = std::cos(phi) * u + std::sin(phi) * v;
    return s.centre + s.major * radial +
           tube_fraction * s.minor * (std::cos(theta) * radial + std::sin(theta) * s.axis);
}

// Ray kinds for the random test.
enum Kind { kNear, kFar, kInsideTube, kGrazing, kAnyDirection, kKinds };

}  // namespace

TEST(random_rays_match_the_distance_walk) {
    Random random(10);
    double worst_g = 0;
    int hits = 0, misses = 0, tangent_hits = 0, grazing_touches = 0, inside_hits = 0, far_hits = 0;
    for (int i = 0; i < 6000; ++i) {
        const TorusSpec s = random_torus(random);
        const Shape shape = s.shape();
        const double reach = s.reach();
        const Kind kind = static_cast<Kind>(i % kKinds);
        Vec3 origin, direction;
        switch (kind) {
            case kNear:
                origin = s.centre + random.in_box(3 * reach);
                direction = normalized(s.centre + random.in_box(reach) - origin);
                break;
            case kFar:
                origin = s.centre + random.unit_vector() * reach * random.uniform(1e3, 1e4);
                direction = normalized(s.centre + random.in_box(reach) - origin);
                break;
            case kInsideTube:
                origin = surface_point(s, random, random.uniform(0, 0.95));
                direction = random.unit_vector();
                break;
            case kGrazing: {
                // Tangent to the surface at a random point, starting well before it.
                const Vec3 p = surface_point(s, random);
                const Vec3 n = normalized(p - s.core_point(p));
                direction = normalized(cross(n, random.unit_vector()));
                origin = p - 2 * reach * direction;
                break;
            }
            default:
                origin = s.centre + random.in_box(2 * reach);
                direction = random.unit_vector();
                break;
        }
        const Ray ray{origin, direction};
        const double t_min = 1e-9;
        const double t_far = length(origin - s.centre) + 2 * reach;
        const auto expected = first_crossing(s, ray, t_min, t_far);
        const auto hit = first_hit(shape, ray);
        // Rounding in the hit point grows with the distance it was measured from.
        const double tolerance = 1e-12 * reach + 1e-14 * length(origin - s.centre);
        if (kind == kInsideTube && s.g(origin) < 0) {
            CHECK(hit.has_value());  // from inside the tube there is always a wall ahead
            if (hit) ++inside_hits;
        }
        if (!hit) {
            ++misses;
            CHECK(!expected.has_value());
            continue;
        }
        ++hits;
        if (kind == kFar) ++far_hits;
        const Vec3 p = ray.at(hit->t);
        CHECK_NEAR(s.g(p), 0.0, tolerance);
        if (kind != kFar) worst_g = std::max(worst_g, std::fabs(s.g(p)) / reach);
        CHECK(shape.bounds().contains(p, tolerance));
        const Vec3 n = shape.normal(p, *hit);
        // The analytic normal, away from the nearest point of the core circle. (At the cusps
        // of a spindle torus there is none.)
        const bool cusp = length(p - s.core_point(p)) < 1e-6 * reach && s.minor >= s.major;
        if (!cusp) CHECK_NEAR(n, (p - s.core_point(p)) / s.minor, 1e-7);
        // Along the ray, the surface's position is uncertain by the tolerance over the
        // cosine of incidence. Closer to tangent than 1e-6 the crossings are within rounding
        // of a double root, uncertain by about the square root of the rounding (1e-6 of the
        // size with the tolerance at 1e-12 of it).
        const double incidence = std::fabs(dot(n, direction));
        const double along_tolerance = tolerance / std::max(incidence, 1e-6);
        if (expected && std::fabs(hit->t - *expected) <= along_tolerance) continue;
        // Otherwise the hit must be a tangency that the walk could not see as a sign change:
        // on the surface (checked above), with the ray along it, and before any crossing.
        const bool tangent = incidence < 1e-3;
        CHECK(tangent);
        CHECK(!expected || hit->t < *expected);
        if (!tangent || (expected && hit->t > *expected)) {
            std::cerr.precision(17);
            std::cerr << "ray " << i << " kind " << kind << ": hit " << hit->t << ", walk "
                      << (expected ? *expected : -1.0) << ", incidence " << incidence << "\n";
        }
        ++(kind == kGrazing ? grazing_touches : tangent_hits);
    }
    std::cout << "  " << hits << " hits\n";
    CHECK(hits > 1500);
    CHECK(misses > 1000);
    CHECK(far_hits > 500);
    CHECK(inside_hits > 1000);
    // Rays built tangent to the surface may report the touch or not; other rays seldom
    // come within rounding of a tangency.
    CHECK(tangent_hits < 10);
    std::cout << hits << " hits, " << misses << " misses, " << grazing_touches
              << " touches of tangent rays, " << tangent_hits << " other tangent hits\n";
    std::cout << "worst |g| at hit points of rays from near by: " << worst_g << " of R + r\n";
}

// Thin tubes (r from 1e-4 to 1e-2 of R): the quartic's coefficients are of the size of
// R + r, so its roots are accurate to rounding of that size, which is coarse beside r; the
// hit is polished on the tube's distance function to rounding of the tube's own size.
TEST(thin_tubes_are_accurate_to_their_own_size) {
    Random random(4);
    int hits = 0;
    for (int i = 0; i < 4000; ++i) {
        const TorusSpec s{random.in_box(2), random.unit_vector(), 1,
                          std::pow(10.0, random.uniform(-4, -2))};
        const Shape shape = s.shape();
        // Aim at the tube: a point of the core circle, moved by up to r.
        const Vec3 target = s.core_point(s.centre + random.in_box(1)) + random.in_box(s.minor);
        const Vec3 origin = s.centre + random.in_box(4);
        const Ray ray{origin, normalized(target - origin)};
        const auto hit = first_hit(shape, ray);
        if (!hit) continue;
        ++hits;
        const Vec3 p = ray.at(hit->t);
        CHECK_NEAR(s.g(p), 0.0, 1e-9 * s.minor);
    }
    std::cout << "  " << hits << " hits\n";
    CHECK(hits > 1500);
}

TEST(rays_in_the_equatorial_plane_through_the_centre) {
    // Along -x from x = 10 through a torus about the y axis: the four crossings are closed
    // form, and each becomes the first when t_min passes the one before.
    const double R = 2, r = 0.5;
    const Shape s = parse_shape("10  0 0 0  0 1 0  2 0.5");
    const Ray ray{{10, 0, 0}, {-1, 0, 0}};
    const double crossings[] = {10 - R - r, 10 - R + r, 10 + R - r, 10 + R + r};
    double t_min = 1e-9;
    for (double expected : crossings) {
        Hit hit;
        CHECK(s.intersect(ray, {t_min, kInfinity}, hit));
        CHECK_NEAR(hit.t, expected, 1e-13);
        t_min = expected + 0.1;
    }
    Hit hit;
    CHECK(!s.intersect(ray, {t_min, kInfinity}, hit));
}

TEST(far_rays_keep_their_accuracy) {
    // A unit torus seen from 1e3 and 1e4 away, head on and edge on.
    const Shape s = parse_shape("10  0 0 0  0 1 0  1 0.25");
    for (double far : {1e3, 1e4}) {
        auto edge_on = first_hit(s, {{far, 0, 0}, {-1, 0, 0}});
        CHECK(edge_on.has_value());
        if (edge_on) CHECK_NEAR(edge_on->t, far - 1.25, 1e-10);
        auto through_tube = first_hit(s, {{1, far, 0}, {0, -1, 0}});
        CHECK(through_tube.has_value());
        if (through_tube) CHECK_NEAR(through_tube->t, far - 0.25, 1e-10);
        // At 45 degrees in the plane z = 0, aimed at the middle of the tube at (1, 0, 0),
        // whose cross-section there is a circle of radius r.
        const Vec3 towards = normalized({-1, -1, 0});
        const auto slanted = first_hit(s, {Vec3{1, 0, 0} - far * towards, towards});
        CHECK(slanted.has_value());
        if (slanted) CHECK_NEAR(slanted->t, far - 0.25, 1e-10);
    }
}

TEST(inside_the_tube_looking_along_it) {
    // From a point of the core circle along its tangent, the ray leaves through the outer
    // wall where its distance from the axis, sqrt(R^2 + t^2), reaches R + r.
    const double R = 3, r = 1;
    const Shape s = parse_shape("10  0 0 0  0 1 0  3 1");
    const auto hit = first_hit(s, {{R, 0, 0}, {0, 0, -1}});
    CHECK(hit.has_value());
    if (hit) CHECK_NEAR(hit->t, std::sqrt((R + r) * (R + r) - R * R), 1e-12);
    // From inside, the outward normal points along the ray.
    if (hit) CHECK(dot(s.normal({R, 0, -hit->t}, *hit), Vec3(0, 0, -1)) > 0);
    // Any direction from inside the tube finds the wall.
    Random random(3);
    for (int i = 0; i < 2000; ++i) {
        const Vec3 o = Vec3{R, 0, 0} + random.unit_vector() * random.uniform(0, 0.99 * r);
        const Ray ray{o, random.unit_vector()};
        const auto wall = first_hit(s, ray);
        CHECK(wall.has_value());
        if (!wall) continue;
        const Vec3 p = ray.at(wall->t);
        const double rho = std::sqrt(p.x * p.x + p.z * p.z);
        CHECK_NEAR(std::sqrt((rho - R) * (rho - R) + p.y * p.y), r, 1e-12);
    }
}

TEST(rays_along_the_axis) {
    const Shape s = parse_shape("10  1 2 3  0 0 2  1.5 0.5");
    // Through the hole: a miss, whichever way and however far.
    CHECK(!first_hit(s, {{1, 2, 100}, {0, 0, -1}}));
    CHECK(!first_hit(s, {{1, 2, -1e4}, {0, 0, 1}}));
    CHECK(!first_hit(s, {{1.9, 2, 100}, {0, 0, -1}}));  // 0.9 off the axis, inside R - r = 1
    // Parallel to the axis through the middle of the tube: hits its top at height r.
    const auto top = first_hit(s, {{2.5, 2, 13}, {0, 0, -1}});
    CHECK(top.has_value());
    if (top) CHECK_NEAR(top->t, 10 - 0.5, 1e-12);
    // A spindle torus (r > R) has no hole: down its axis the ray meets its dimple, where the
    // tube reaches the axis at height sqrt(r^2 - R^2).
    const Shape spindle = parse_shape("10  0 0 0  0 1 0  0.6 1");
    const auto dimple = first_hit(spindle, {{0, 5, 0}, {0, -1, 0}});
    CHECK(dimple.has_value());
    if (dimple) CHECK_NEAR(dimple->t, 5 - 0.8, 1e-7);
}

TEST(spindle_torus_shows_only_its_outer_surface) {
    // R = 1, r = 2: from inside, near the centre, rays cross the inner "lemon" of the
    // quartic (where the tube overlaps itself); the first surface is the outer one.
    const Shape s = parse_shape("10  0 0 0  0 0 1  1 2");
    const auto sideways = first_hit(s, {{0, 0, 0}, {1, 0, 0}});
    CHECK(sideways.has_value());
    if (sideways) CHECK_NEAR(sideways->t, 3, 1e-12);
    // Along the axis from the centre the outer surface is the dimple at sqrt(r^2 - R^2).
    const auto up = first_hit(s, {{0, 0, 0}, {0, 0, 1}});
    CHECK(up.has_value());
    if (up) CHECK_NEAR(up->t, std::sqrt(3.0), 1e-7);
    CHECK(s.inside({0, 0, 0}));
    CHECK(s.inside({0, 0, 1.7}));
    CHECK(!s.inside({0, 0, 1.8}));
}

TEST(grazing_rays) {
    // Along x at height y over a torus about the y axis: the plane z = 0 cuts the tube in
    // circles of radius r about (+-R, 0), so at y = r the ray touches the tube and just
    // below it crosses at x = -R - sqrt(r^2 - y^2).
    const double R = 1, r = 0.25;
    const Shape s = parse_shape("10  0 0 0  0 1 0  1 0.25");
    CHECK(!first_hit(s, {{-10, r + 1e-6, 0}, {1, 0, 0}}));
    for (double below : {1e-3, 1e-6, 1e-9}) {
        const double y = r - below;
        const auto hit = first_hit(s, {{-10, y, 0}, {1, 0, 0}});
        CHECK(hit.has_value());
        if (hit) CHECK_NEAR(hit->t, 10 - R - std::sqrt(r * r - y * y), 1e-9);
    }
    // Tangent to the outer equator from outside: touching the surface at one point.
    const auto touch = first_hit(s, {{-10, 0, R + r - 1e-9}, {1, 0, 0}});
    CHECK(touch.has_value());
    if (touch) CHECK_NEAR(touch->t, 10, 1e-3);
}

TEST(best_distance_so_far_stops_early) {
    const Shape s = parse_shape("10  0 0 0  0 1 0  2 0.5");
    const Ray ray{{10, 0, 0}, {-1, 0, 0}};  // first hit at 7.5
    Hit hit{123, 7};
    CHECK(!s.intersect(ray, {1e-9, 7.4}, hit));
    CHECK_EQ(hit.t, 123.0);                    // left alone on a miss
    CHECK(!s.intersect(ray, {1e-9, 1}, hit));  // the whole torus is beyond t_max
    CHECK_EQ(hit.t, 123.0);
    CHECK(s.intersect(ray, {1e-9, 7.6}, hit));
    CHECK_NEAR(hit.t, 7.5, 1e-12);
    CHECK(!first_hit(s, {{10, 0, 0}, {1, 0, 0}}));  // pointing away
    // Inside the bounding sphere before t_max, but the first root is beyond it: along -z at
    // height 0.3 the ray meets the sphere of radius R + r at 10 - sqrt(6.25 - 0.09) = 7.52
    // and the tube first at 10 - (R + sqrt(r^2 - 0.09)) = 7.6.
    const Ray high{{0, 0.3, 10}, {0, 0, -1}};
    Hit untouched{123, 7};
    CHECK(!s.intersect(high, {1e-9, 7.55}, untouched));
    CHECK_EQ(untouched.t, 123.0);
    CHECK(s.intersect(high, {1e-9, 7.65}, untouched));
    CHECK_NEAR(untouched.t, 7.6, 1e-12);
}

// Finding 16 of issue 21: two overlapping tori whose tube is 2^26 times their major radius
// rendered differently through the hierarchy and the linear scan, because a root straight
// from the quartic (imprecise at such shapes) was compared with the range before it was
// polished, so a narrower t_max (the nearest hit so far) could reject the right root. A hit
// must not depend on the range it is asked within: inside any range that holds it, the
// same distance; outside, none.
TEST(a_hit_does_not_depend_on_the_range_asked_within) {
    Random random(21);
    int hits = 0;
    for (const double minor : {0.5, 3.0, 1e3, 1e6, 67108864.0, 1e9, 1e12, 1e15}) {
        const Shape s = parse_shape(object_text(10, {0, 0.4, 0, 0, 0.6, 0.8, 1, minor}));
        for (int i = 0; i < 400; ++i) {
            const double spread = i % 2 ? 3 : 2 * minor;
            const Vec3 origin = random.in_box(spread);
            const Ray ray{origin, random.unit_vector()};
            Hit full;
            if (!s.intersect(ray, {1e-9, kInfinity}, full)) continue;
            ++hits;
            const double t = full.t;
            for (const double above : {1e-12, 1e-9, 1e-6, 1e-3, 0.1}) {
                Hit narrowed;
                CHECK(s.intersect(ray, {1e-9, t + above * (1 + t)}, narrowed));
                CHECK_EQ(narrowed.t, t);
            }
            Hit none;
            CHECK(!s.intersect(ray, {1e-9, t}, none));
            if (t > 1) {
                Hit later;  // from a little before the hit: the same one
                CHECK(s.intersect(ray, {t * (1 - 1e-9), kInfinity}, later));
                CHECK_EQ(later.t, t);
            }
        }
    }
    std::cout << "  " << hits << " hits\n";
    CHECK(hits > 1500);
}

// The same through whole renders: the hierarchy and the linear scan give the same bytes for
// overlapping tori at extreme radii, seen from inside and outside.
TEST(hierarchy_and_linear_scan_agree_on_extreme_tori) {
    for (const char* minor : {"1.5", "1e6", "67108864", "1e12", "1e18"}) {
        for (const char* eye : {"0 0 -3", "1 2 3", "0 0 -1e20"}) {
            const std::string text = join("102  ", eye,
                                          "  0 0 0  0.5 0 0  0 0.375 0  40 30\n"
                                          "103  0.2 0.2 0.2\n101  -4 8 -6  60 60 60\n"
                                          "10  0 0.4 0  0 0 1  1 ",
                                          minor,
                                          "  100 1 0 0  0 1 0.8 0 1\n"
                                          "10  0 0.3 0  0 0 1  1 ",
                                          minor, "  100 0 1 0  0 1 0.8 0 1\n");
            const Scene scene = parse_scene(text);
            RenderOptions linear;
            linear.accelerate = false;
            const Raster a = render(scene, RenderOptions{});
            const Raster b = render(scene, linear);
            int differ = 0;
            for (int y = 0; y < a.height(); ++y)
                for (int x = 0; x < a.width(); ++x)
                    for (std::size_t c = 0; c < 3; ++c) differ += a.at(x, y)[c] != b.at(x, y)[c];
            CHECK_EQ(differ, 0);
        }
    }
}

TEST(inside_test) {
    const TorusSpec spec{{1, -2, 0.5}, normalized({1, 2, -2}), 1.5, 0.4};
    const Shape s = spec.shape();
    CHECK(s.has_inside());
    CHECK(!s.inside(spec.centre));  // the hole
    Random random(8);
    for (int i = 0; i < 2000; ++i) {
        const Vec3 in = surface_point(spec, random, random.uniform(0, 0.99));
        const Vec3 out = surface_point(spec, random, random.uniform(1.01, 3));
        CHECK(s.inside(in));
        CHECK(!s.inside(out));
    }
}

TEST(bounds_are_tight) {
    // Axis along z: the box is R + r wide in x and y, r in z.
    const Bounds b = parse_shape("10  1 2 3  0 0 -4  2 0.5").bounds();
    CHECK_NEAR(b.min, Vec3(-1.5, -0.5, 2.5), 1e-15);
    CHECK_NEAR(b.max, Vec3(3.5, 4.5, 3.5), 1e-15);
}

// The scenes, traced as the renderer does: every primary ray of the inside view must meet
// the wall (a miss would be a hole), and rays leaving a torus must not find it again at
// their own origin (acne: speckles of false shadow or reflection). Each is sampled on a grid
// twice as fine as the image.
TEST(scenes_have_no_holes_or_acne) {
    for (const char* name : {"torus.in", "torus-inside.in"}) {
        const Scene scene = read_scene_file(join(RT_SOURCE_DIR, "/scenes/", name));
        const RenderOptions options;
        Tracer tracer(scene, options);
        const bool inside_view = std::string(name) == "torus-inside.in";
        int holes = 0, acne = 0, leaving_rays = 0;
        constexpr int kSubsamples = 2;
        for (int y = 0; y < scene.viewer.yres * kSubsamples; ++y) {
            for (int x = 0; x < scene.viewer.xres * kSubsamples; ++x) {
                const Ray ray =
                    scene.viewer.primary_ray((x + 0.5) / kSubsamples, (y + 0.5) / kSubsamples);
                const auto found = tracer.closest_hit(ray);
                if (!found) {
                    holes += inside_view;
                    continue;
                }
                if (found->object->shape.type->id != 10) continue;
                const Vec3 p = ray.at(found->hit.t);
                Vec3 n = found->object->shape.normal(p, found->hit);
                if (dot(n, ray.direction) > 0) n = -n;  // facing the ray, as the tracer does
                // Reflected rays and rays towards each light, where they leave the surface
                // clearly (not within 1e-2 of tangent, where a near hit may be genuine).
                std::vector<Vec3> leaving{reflect(ray.direction, n)};
                for (const Light& light : scene.lights)
                    leaving.push_back(light.sample(p, 0).direction);
                for (const Vec3& d : leaving) {
                    if (!(dot(d, n) > 1e-2)) continue;
                    ++leaving_rays;
                    const auto again = tracer.closest_hit({p, d});
                    if (again && again->hit.t < 1e-4) ++acne;
                }
            }
        }
        CHECK_EQ(holes, 0);
        CHECK_EQ(acne, 0);
        CHECK(leaving_rays > 20000);
    }
}

TEST(read_errors) {
    auto scene = [](const std::string& torus) {
        return scene_error(join(kTestViewer, torus, "  100 1 1 1 0 1 1 0 1\n"));
    };
    CHECK_EQ(scene("10  0 0 0  0 1 0  1 0.5"), "");
    CHECK_CONTAINS(scene("10  0 0 0  0 0 0  1 0.5"),
                   "test.in:2:12: torus axis must have a non-zero length");
    CHECK_CONTAINS(scene("10  0 0 0  0 1 0  0 0.5"),
                   "test.in:2:19: torus major radius must be > 0, got 0");
    CHECK_CONTAINS(scene("10  0 0 0  0 1 0  -2 0.5"),
                   "test.in:2:19: torus major radius must be > 0, got -2");
    CHECK_CONTAINS(scene("10  0 0 0  0 1 0  1 0"),
                   "test.in:2:21: torus minor radius must be > 0, got 0");
    CHECK_CONTAINS(scene("10  0 0 0  0 1 0  1 -0.5"),
                   "test.in:2:21: torus minor radius must be > 0, got -0.5");
    CHECK_CONTAINS(scene_error(join(kTestViewer, "10  0 0 0  0 1 0  1")),
                   "unexpected end of file: expected torus minor radius");
}
