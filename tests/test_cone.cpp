// Cone (ID 8) against the closed form: in a frame whose z axis is the cone's axis the double
// cone is x^2 + y^2 = tan^2(theta) z^2, solved here in long double, independently of the
// world-frame quadratic the code uses.
#include <algorithm>
#include <cmath>
#include <vector>

#include "random_rays.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

const std::string kSurface = " 100 1 1 1 0 1 1 0 1\n";

struct ConeSpec {
    double alpha, start, finish;
    Vec3 apex, axis;

    Shape shape() const {
        return parse_shape(
            object_text(8, {alpha, start, finish, apex.x, apex.y, apex.z, axis.x, axis.y, axis.z}));
    }
    // (x - c).a / |a|^2: the extent coordinate the contract defines.
    double extent_of(const Vec3& x) const { return dot(x - apex, axis) / length_squared(axis); }
};

// Ambiguous for a tangent ray or a root at the rim.
ClosedForm closed_form(const ConeSpec& k, const Ray& ray) {
    const Frame f = frame_around(k.axis);
    const Vec3 o = f.local(ray.origin - k.apex), d = f.local(ray.direction);
    using ld = long double;
    const ld tan2 = (1.0L - ld(k.alpha) * k.alpha) / (ld(k.alpha) * k.alpha);
    const ld a = ld(d.x) * d.x + ld(d.y) * d.y - tan2 * d.z * d.z;
    const ld b = ld(o.x) * d.x + ld(o.y) * d.y - tan2 * o.z * d.z;
    const ld c = ld(o.x) * o.x + ld(o.y) * o.y - tan2 * o.z * o.z;
    const ld disc = b * b - a * c;
    ClosedForm e;
    if (std::fabs(disc) < 1e-9L * (b * b + std::fabs(a * c))) e.ambiguous = true;
    if (disc < 0) return e;
    std::vector<ld> roots;
    const ld q = -(b + (b < 0 ? -1 : 1) * std::sqrt(disc));
    if (a != 0) roots.push_back(q / a);
    if (q != 0) roots.push_back(c / q);
    std::sort(roots.begin(), roots.end());
    const double len = length(k.axis);
    for (const ld t : roots)
        e.crossing(t, static_cast<double>((o.z + t * d.z) / len), k.start, k.finish);
    return e;
}

// The outward normal from the local gradient of x^2 + y^2 - tan^2 z^2.
Vec3 closed_form_normal(const ConeSpec& k, const Vec3& p) {
    const Frame f = frame_around(k.axis);
    const Vec3 v = f.local(p - k.apex);
    const double tan2 = (1 - k.alpha * k.alpha) / (k.alpha * k.alpha);
    return normalized(f.world({v.x, v.y, -tan2 * v.z}));
}

std::string cone_scene(const std::string& numbers) {
    return join(kTestViewer, "8 ", numbers, kSurface);
}

}  // namespace

TEST(random_rays_match_closed_form) {
    Random random(8);
    RayCounts counts;
    int from_inside = 0, second_root = 0, both_nappes = 0;
    for (int i = 0; i < 20000; ++i) {
        ConeSpec k;
        k.alpha = random.uniform(0.2, 0.95);
        k.start = random.uniform(-2, 1);
        k.finish = k.start + random.uniform(0.2, 2.5);
        k.apex = random.in_box(4);
        k.axis = random.unit_vector() * random.uniform(0.3, 3);
        const Shape s = k.shape();
        const Frame f = frame_around(k.axis);
        const double tan = std::sqrt(1 - k.alpha * k.alpha) / k.alpha;
        const double len = length(k.axis);
        // A point near the surface inside the extent, to aim at or start from.
        const double h = random.uniform(k.start, k.finish) * len;
        const double phi = random.uniform(0, 6.283185307179586);
        const Vec3 near_surface =
            k.apex + f.world({std::fabs(h) * tan * std::cos(phi) * random.uniform(0.5, 1.5),
                              std::fabs(h) * tan * std::sin(phi) * random.uniform(0.5, 1.5), h});
        Ray ray;
        switch (i % 5) {
            case 0:  // from anywhere toward the surface
                ray.origin = random.in_box(10);
                ray.direction = normalized(near_surface + random.in_box(0.3) - ray.origin);
                break;
            case 1:  // from inside the solid cone (inside a nappe)
                ray.origin = k.apex + f.world({0.3 * h * tan * std::cos(phi),
                                               0.3 * h * tan * std::sin(phi), h});
                ray.direction = random.unit_vector();
                break;
            case 2:  // along the axis, from off it
                ray.origin = near_surface + random.in_box(2);
                ray.direction = normalized(k.axis) * (i % 2 ? 1 : -1);
                break;
            case 3: {  // parallel to a generator line: the quadratic degenerates to linear
                const double psi = random.uniform(0, 6.283185307179586);
                const double sin = std::sqrt(1 - k.alpha * k.alpha);
                ray.direction =
                    f.world({sin * std::cos(psi), sin * std::sin(psi), k.alpha}) * (i % 2 ? 1 : -1);
                ray.origin = near_surface + random.in_box(2);
                break;
            }
            default:  // anything
                ray = any_ray(random);
        }
        const ClosedForm expected = closed_form(k, ray);
        const auto found = compare_first_hit(s, ray, expected, 1e-9, counts);
        if (!found) continue;
        if (i % 5 == 1) ++from_inside;
        const Vec3 p = found->point;
        const Vec3 v = p - k.apex;
        const double along = dot(v, normalized(k.axis));
        // On the double cone, within the extent, in the bounds.
        CHECK_NEAR(along * along, k.alpha * k.alpha * length_squared(v),
                   1e-8 * (1 + length_squared(v)));
        const double e = k.extent_of(p);
        CHECK(e >= k.start - 1e-9 && e <= k.finish + 1e-9);
        CHECK(s.bounds().contains(p, 1e-9));
        // The normal matches the gradient and points away from the axis on either nappe.
        const Vec3 n = s.normal(p, found->hit);
        CHECK_NEAR(n, closed_form_normal(k, p), 1e-7);
        CHECK(dot(n, v - along * normalized(k.axis)) > 0);
        if (along < 0) ++both_nappes;
        if (expected.nearer_clipped) ++second_root;
    }
    CHECK(counts.hits > 4000);
    CHECK(counts.misses > 4000);
    CHECK(from_inside > 1000);
    CHECK(both_nappes > 1000);
    CHECK(second_root > 500);
    CHECK(counts.skipped < 400);
}

TEST(original_example_runs_ten_units_down) {
    // 0.9; from 0 to 2; apex (0,2,0); axis (0,-5,0): from y = 2 down to y = -8.
    const Shape s = parse_shape("8  0.9  0 2  0 2 0  0 -5 0");
    const double tan = std::sqrt(1 - 0.81) / 0.9;
    for (const double y : {1.999, 1.0, -3.0, -7.999}) {
        const auto hit = first_hit(s, {{-20, y, 0}, {1, 0, 0}});
        CHECK(hit.has_value());
        if (hit) CHECK_NEAR(hit->t, 20 - (2 - y) * tan, 1e-9);
    }
    // Above the apex (the other nappe, clipped away) and below y = -8 the rays miss.
    CHECK(!first_hit(s, {{-20, 2.001, 0}, {1, 0, 0}}));
    CHECK(!first_hit(s, {{-20, -8.001, 0}, {1, 0, 0}}));
    // The rim is exactly at y = -8 and the radius there is 10 tan.
    const Bounds b = s.bounds();
    CHECK_NEAR(b.min.y, -8.0, 1e-12);
    CHECK_NEAR(b.max.y, 2.0, 1e-12);
    CHECK_NEAR(b.max.x, 10 * tan, 1e-12);
    CHECK_NEAR(b.min.z, -10 * tan, 1e-12);
}

TEST(ray_along_axis_meets_apex) {
    const Shape s = parse_shape("8  0.9  0 2  0 2 0  0 -5 0");
    const auto hit = first_hit(s, {{0, -20, 0}, {0, 1, 0}});
    CHECK(hit.has_value());
    if (hit) {
        CHECK_NEAR(hit->t, 22, 1e-9);
        const Vec3 n = s.normal({0, 2, 0}, *hit);
        CHECK(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
        CHECK_NEAR(length(n), 1.0, 1e-12);
    }
}

TEST(far_wall_seen_through_the_mouth) {
    // A ray from below and beside the example cone crosses the infinite cone first below
    // y = -8 (clipped away), then meets the inside of the far wall at y = -3.
    const Shape s = parse_shape("8  0.9  0 2  0 2 0  0 -5 0");
    const double tan = std::sqrt(1 - 0.81) / 0.9;
    const Vec3 target{5 * tan, -3, 0};
    const Vec3 origin{-12, -14, 0};
    const Ray ray{origin, normalized(target - origin)};
    const ConeSpec k{0.9, 0, 2, {0, 2, 0}, {0, -5, 0}};
    // The nearer root of the unclipped cone lies outside the extent, so the test means it.
    const ConeSpec unclipped{0.9, -100, 100, {0, 2, 0}, {0, -5, 0}};
    const auto nearer = closed_form(unclipped, ray).t;
    CHECK(nearer.has_value());
    if (nearer) CHECK(k.extent_of(ray.at(*nearer)) > 2);
    const auto hit = first_hit(s, ray);
    CHECK(hit.has_value());
    if (hit) {
        CHECK_NEAR(hit->t, length(target - origin), 1e-9);
        // The outward normal faces away from the axis; the ray sees its back.
        CHECK(dot(s.normal(ray.at(hit->t), *hit), ray.direction) > 0);
    }
}

TEST(normals_on_both_nappes) {
    // Half-angle 45 degrees, apex at the origin, axis +z, from z = -1 to z = 1.
    const Shape s = parse_shape(object_text(8, {std::sqrt(0.5), -1, 1, 0, 0, 0, 0, 0, 1}));
    const auto upper = first_hit(s, {{5, 0, 1}, {-1, 0, 0}});
    CHECK(upper.has_value());
    if (upper) {
        CHECK_NEAR(upper->t, 4, 1e-12);
        CHECK_NEAR(s.normal({1, 0, 1}, *upper), Vec3(1, 0, -1) / std::sqrt(2.0), 1e-12);
    }
    const auto lower = first_hit(s, {{5, 0, -1}, {-1, 0, 0}});
    CHECK(lower.has_value());
    if (lower) {
        CHECK_NEAR(lower->t, 4, 1e-12);
        CHECK_NEAR(s.normal({1, 0, -1}, *lower), Vec3(1, 0, 1) / std::sqrt(2.0), 1e-12);
    }
    CHECK_NEAR(s.normal({0, -2, 2}, Hit{}), Vec3(0, -1, -1) / std::sqrt(2.0), 1e-12);
    CHECK_NEAR(s.normal({0, -2, -2}, Hit{}), Vec3(0, -1, 1) / std::sqrt(2.0), 1e-12);
}

TEST(best_distance_so_far_stops_early) {
    const Shape s = parse_shape("8  0.9  0 2  0 2 0  0 -5 0");
    const Ray ray{{-20, 0, 0}, {1, 0, 0}};
    const double tan = std::sqrt(1 - 0.81) / 0.9;
    Hit hit{123, 7};
    CHECK(!s.intersect(ray, {1e-9, 20 - 2 * tan - 0.01}, hit));
    CHECK_EQ(hit.t, 123.0);
    // Past the near wall, the far wall is the next hit.
    CHECK(s.intersect(ray, {20 - 2 * tan + 0.01, kInfinity}, hit));
    CHECK_NEAR(hit.t, 20 + 2 * tan, 1e-9);
}

TEST(read_errors_name_the_field) {
    CHECK_CONTAINS(scene_error(cone_scene("0 0 2 0 2 0 0 -5 0")),
                   "test.in:2:3: cone alpha (cos of the half-angle) must be > 0 and < 1, got 0");
    CHECK_CONTAINS(scene_error(cone_scene("1 0 2 0 2 0 0 -5 0")),
                   "test.in:2:3: cone alpha (cos of the half-angle) must be > 0 and < 1, got 1");
    CHECK_CONTAINS(scene_error(cone_scene("-0.5 0 2 0 2 0 0 -5 0")),
                   "test.in:2:3: cone alpha (cos of the half-angle) must be > 0 and < 1");
    CHECK_CONTAINS(scene_error(cone_scene("1.5 0 2 0 2 0 0 -5 0")),
                   "test.in:2:3: cone alpha (cos of the half-angle) must be > 0 and < 1");
    CHECK_CONTAINS(scene_error(cone_scene("0.9 2 0 0 2 0 0 -5 0")),
                   "test.in:2:9: cone finish must be greater than start 2, got 0");
    CHECK_CONTAINS(scene_error(cone_scene("0.9 1 1 0 2 0 0 -5 0")),
                   "test.in:2:9: cone finish must be greater than start 1, got 1");
    CHECK_CONTAINS(scene_error(cone_scene("0.9 0 2 0 2 0 0 0 0")),
                   "test.in:2:17: cone axis must have a non-zero length");
    CHECK_CONTAINS(scene_error(cone_scene("0.9 0 1e300 0 2 0 1e10 0 0")),
                   "test.in:2:21: cone start and finish times the axis length (1e+10) must be "
                   "finite and distinct");
    CHECK_CONTAINS(scene_error(join(kTestViewer, "8 0.9 0 2 0 2 0 0 -5")),
                   "unexpected end of file: expected cone axis");
    CHECK_EQ(scene_error(cone_scene("0.9 0 2 0 2 0 0 -5 0")), std::string());
}
