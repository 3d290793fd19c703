// Cylinder (ID 9) against the closed form: in a frame whose z axis is the cylinder's axis the
// ray's shadow on the xy-plane meets the circle of radius r, solved geometrically (the
// chord's half-length from the shadow's distance to the centre), not as the quadratic the
// code uses.
#include <cmath>
#include <vector>

#include "random_rays.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

const std::string kSurface = " 100 1 1 1 0 1 1 0 1\n";

struct CylinderSpec {
    double radius, start, finish;
    Vec3 centre, axis;

    Shape shape() const {
        return parse_shape(object_text(
            9, {radius, start, finish, centre.x, centre.y, centre.z, axis.x, axis.y, axis.z}));
    }
    // (x - c).a / |a|^2: the extent coordinate the contract defines.
    double extent_of(const Vec3& x) const { return dot(x - centre, axis) / length_squared(axis); }
};

// Ambiguous for a tangent ray or a root at the rim.
ClosedForm closed_form(const CylinderSpec& k, const Ray& ray) {
    const Frame f = frame_around(k.axis);
    const Vec3 o = f.local(ray.origin - k.centre), d = f.local(ray.direction);
    ClosedForm e;
    const double shadow = std::hypot(d.x, d.y);
    if (shadow == 0) return e;  // parallel to the axis: never crosses the wall
    const double ux = d.x / shadow, uy = d.y / shadow;
    const double closest = -(o.x * ux + o.y * uy);       // along the shadow, to the nearest point
    const double miss = std::fabs(o.x * uy - o.y * ux);  // distance of the shadow line
    if (std::fabs(miss - k.radius) < 1e-9 * k.radius) e.ambiguous = true;
    if (miss > k.radius) return e;
    const double half = std::sqrt((k.radius - miss) * (k.radius + miss));
    for (const double along : {closest - half, closest + half}) {
        const double t = along / shadow;
        e.crossing(t, (o.z + t * d.z) / length(k.axis), k.start, k.finish);
    }
    return e;
}

std::string cylinder_scene(const std::string& numbers) {
    return join(kTestViewer, "9 ", numbers, kSurface);
}

}  // namespace

TEST(random_rays_match_closed_form) {
    Random random(9);
    RayCounts counts;
    int from_inside = 0, nearer_clipped = 0, parallel = 0;
    for (int i = 0; i < 20000; ++i) {
        CylinderSpec k;
        k.radius = random.uniform(0.1, 2);
        k.start = random.uniform(-2, 1);
        k.finish = k.start + random.uniform(0.2, 3);
        k.centre = random.in_box(4);
        k.axis = random.unit_vector() * random.uniform(0.3, 3);
        const Shape s = k.shape();
        const Vec3 unit_axis = normalized(k.axis);
        const double len = length(k.axis);
        // A point on the axis within the extent, and a unit vector across the axis.
        const Vec3 on_axis = k.centre + unit_axis * (random.uniform(k.start, k.finish) * len);
        const Vec3 r = random.unit_vector();
        const Vec3 across = normalized(r - dot(r, unit_axis) * unit_axis);
        Ray ray;
        switch (i % 5) {
            case 0:  // from anywhere toward the wall
                ray.origin = random.in_box(10);
                ray.direction =
                    normalized(on_axis + across * (k.radius * random.uniform(0, 1.5)) - ray.origin);
                break;
            case 1:  // from inside
                ray.origin = on_axis + across * (k.radius * random.uniform(0, 0.95));
                ray.direction = random.unit_vector();
                break;
            case 2:  // exactly along the axis, inside or outside
                ray.origin = on_axis + across * (k.radius * random.uniform(0, 2));
                ray.direction = unit_axis * (i % 2 ? 1 : -1);
                break;
            case 3:  // nearly along the axis
                ray.origin = on_axis + across * (k.radius * random.uniform(0, 2));
                ray.direction = normalized(unit_axis + random.in_box(1e-3));
                break;
            default:  // anything
                ray = any_ray(random);
        }
        const ClosedForm expected = closed_form(k, ray);
        if (i % 5 == 2 && !expected.ambiguous) {
            ++parallel;
            CHECK(!first_hit(s, ray));
        }
        const auto found = compare_first_hit(s, ray, expected, 1e-9, counts);
        if (!found) continue;
        if (i % 5 == 1) ++from_inside;
        if (expected.nearer_clipped) ++nearer_clipped;
        const Vec3 p = found->point;
        const Vec3 v = p - k.centre;
        const Vec3 radial = v - dot(v, unit_axis) * unit_axis;
        CHECK_NEAR(length(radial), k.radius, 1e-9 * (1 + length(v)));
        const double e = k.extent_of(p);
        CHECK(e >= k.start - 1e-9 && e <= k.finish + 1e-9);
        CHECK(s.bounds().contains(p, 1e-9));
        // Outward (away from the axis) even when seen from inside; the tracer flips it.
        CHECK_NEAR(s.normal(p, found->hit), radial / k.radius, 1e-8);
    }
    CHECK(counts.hits > 5000);
    CHECK(counts.misses > 4000);
    CHECK(from_inside > 2000);
    CHECK(nearer_clipped > 300);
    CHECK(parallel > 3000);
    CHECK(counts.skipped < 400);
}

TEST(original_example_runs_from_2_down_to_minus_8) {
    // Radius 0.5; from 0 to 10; point (0,2,0); axis (0,-1,0).
    const Shape s = parse_shape("9  0.5  0 10  0 2 0  0 -1 0");
    for (const double y : {1.999, 0.0, -5.0, -7.999}) {
        const auto hit = first_hit(s, {{-20, y, 0}, {1, 0, 0}});
        CHECK(hit.has_value());
        if (hit) CHECK_NEAR(hit->t, 19.5, 1e-12);
    }
    CHECK(!first_hit(s, {{-20, 2.001, 0}, {1, 0, 0}}));
    CHECK(!first_hit(s, {{-20, -8.001, 0}, {1, 0, 0}}));
    const Bounds b = s.bounds();
    CHECK_NEAR(b.min, Vec3(-0.5, -8, -0.5), 1e-12);
    CHECK_NEAR(b.max, Vec3(0.5, 2, 0.5), 1e-12);
}

TEST(from_inside_the_normal_still_points_out) {
    const Shape s = parse_shape("9  0.5  0 10  0 2 0  0 -1 0");
    const auto hit = first_hit(s, {{0, 0, 0}, {1, 0, 0}});
    CHECK(hit.has_value());
    if (hit) {
        CHECK_NEAR(hit->t, 0.5, 1e-12);
        CHECK_NEAR(s.normal({0.5, 0, 0}, *hit), Vec3(1, 0, 0), 1e-12);
    }
}

TEST(inside_wall_seen_through_the_open_end) {
    // From above the top (y = 2), the ray first crosses the infinite cylinder at y = 7
    // (clipped away) and then meets the far wall inside at y = -3.
    const Shape s = parse_shape("9  0.5  0 10  0 2 0  0 -1 0");
    const Vec3 origin{-1, 12, 0}, target{0.5, -3, 0};
    const Ray ray{origin, normalized(target - origin)};
    const CylinderSpec unclipped{0.5, -100, 100, {0, 2, 0}, {0, -1, 0}};
    const auto nearer = closed_form(unclipped, ray).t;
    CHECK(nearer.has_value());
    if (nearer) CHECK_NEAR(ray.at(*nearer).y, 7.0, 1e-9);
    const auto hit = first_hit(s, ray);
    CHECK(hit.has_value());
    if (hit) CHECK_NEAR(hit->t, length(target - origin), 1e-9);
}

TEST(rays_along_the_axis_never_hit) {
    const Shape s = parse_shape("9  0.5  0 10  0 2 0  0 -1 0");
    CHECK(!first_hit(s, {{0, 20, 0}, {0, -1, 0}}));
    CHECK(!first_hit(s, {{0.2, -3, 0.1}, {0, 1, 0}}));
    CHECK(!first_hit(s, {{3, -3, 0}, {0, 1, 0}}));
    // Exactly on the wall, running along it: no single crossing, so no hit (and no NaN).
    CHECK(!first_hit(s, {{0.5, 5, 0}, {0, -1, 0}}));
}

TEST(best_distance_so_far_stops_early) {
    const Shape s = parse_shape("9  0.5  0 10  0 2 0  0 -1 0");
    const Ray ray{{-20, 0, 0}, {1, 0, 0}};
    Hit hit{123, 7};
    CHECK(!s.intersect(ray, {1e-9, 19.4}, hit));
    CHECK_EQ(hit.t, 123.0);
    CHECK(s.intersect(ray, {19.6, kInfinity}, hit));
    CHECK_NEAR(hit.t, 20.5, 1e-12);
}

TEST(read_errors_name_the_field) {
    CHECK_CONTAINS(scene_error(cylinder_scene("0 0 10 0 2 0 0 -1 0")),
                   "test.in:2:3: cylinder radius must be > 0, got 0");
    CHECK_CONTAINS(scene_error(cylinder_scene("-0.5 0 10 0 2 0 0 -1 0")),
                   "test.in:2:3: cylinder radius must be > 0, got -0.5");
    CHECK_CONTAINS(scene_error(cylinder_scene("0.5 10 0 0 2 0 0 -1 0")),
                   "test.in:2:10: cylinder finish must be greater than start 10, got 0");
    CHECK_CONTAINS(scene_error(cylinder_scene("0.5 3 3 0 2 0 0 -1 0")),
                   "test.in:2:9: cylinder finish must be greater than start 3, got 3");
    CHECK_CONTAINS(scene_error(cylinder_scene("0.5 0 10 0 2 0 0 0 0")),
                   "test.in:2:18: cylinder axis must have a non-zero length");
    CHECK_CONTAINS(scene_error(cylinder_scene("0.5 -1e300 10 0 2 0 1e10 0 0")),
                   "test.in:2:23: cylinder start and finish times the axis length (1e+10) must "
                   "be finite and distinct");
    CHECK_CONTAINS(scene_error(join(kTestViewer, "9 0.5 0 10 0 2")),
                   "unexpected end of file: expected cylinder point on axis");
    CHECK_EQ(scene_error(cylinder_scene("0.5 0 10 0 2 0 0 -1 0")), std::string());
}
