// Box (ID 12) against the closed form: each of the six faces intersected as a rectangle in
// its own plane, the nearest accepted, independently of the slab method the code uses.
#include <cmath>

#include "random_rays.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

const std::string kSurface = " 100 1 1 1 0 1 1 0 1\n";

struct BoxSpec {
    Vec3 min, max;
    Shape shape() const {
        return parse_shape(object_text(12, {min.x, min.y, min.z, max.x, max.y, max.z}));
    }
};

// Ambiguous where the hit is on an edge, or the ray skims a face.
struct Expected : ClosedForm {
    Vec3 normal;
};

// The slack by which a point still counts as on a face's rectangle.
constexpr double kEdgeSlack = 1e-9;

Expected closed_form(const BoxSpec& b, const Ray& ray) {
    Expected e;
    for (int axis = 0; axis < 3; ++axis) {
        if (ray.direction[axis] == 0) continue;
        for (const bool at_max : {false, true}) {
            const double plane = at_max ? b.max[axis] : b.min[axis];
            const double t = (plane - ray.origin[axis]) / ray.direction[axis];
            if (!(t > 1e-6)) continue;
            const Vec3 p = ray.at(t);
            bool on_face = true, near_edge = false;
            for (int other = 0; other < 3; ++other) {
                if (other == axis) continue;
                const double lo = b.min[other], hi = b.max[other];
                if (p[other] < lo - kEdgeSlack || p[other] > hi + kEdgeSlack) on_face = false;
                if (std::fabs(p[other] - lo) < 1e-7 || std::fabs(p[other] - hi) < 1e-7)
                    near_edge = true;
            }
            if (!on_face) continue;
            if (near_edge) e.ambiguous = true;
            if (!e.t || t < *e.t) {
                e.t = t;
                e.normal = Vec3(axis == 0, axis == 1, axis == 2) * (at_max ? 1.0 : -1.0);
            }
        }
    }
    return e;
}

std::string box_scene(const std::string& numbers) {
    return join(kTestViewer, "12 ", numbers, kSurface);
}

bool finite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

TEST(random_rays_match_closed_form) {
    Random random(12);
    RayCounts counts;
    int from_inside = 0, axis_parallel = 0;
    for (int i = 0; i < 20000; ++i) {
        const Vec3 a = random.in_box(4),
                   size{random.uniform(0.1, 3), random.uniform(0.1, 3), random.uniform(0.1, 3)};
        const BoxSpec b{a, a + size};
        const Shape s = b.shape();
        const Vec3 centre = a + size * 0.5;
        const Vec3 wide{size.x * random.uniform(-0.8, 0.8), size.y * random.uniform(-0.8, 0.8),
                        size.z * random.uniform(-0.8, 0.8)};
        Ray ray;
        switch (i % 4) {
            case 0:  // from outside toward it
                ray.origin = random.in_box(10);
                ray.direction = normalized(centre + wide - ray.origin);
                break;
            case 1:  // from inside
                ray.origin = centre + wide * 0.6;
                ray.direction = random.unit_vector();
                break;
            case 2: {  // along a coordinate axis
                ray.origin = centre + wide + random.in_box(3);
                const int axis = static_cast<int>(random.uniform(0, 3));
                const double sign = i % 8 < 4 ? 1 : -1;
                ray.direction = Vec3(axis == 0, axis == 1, axis == 2) * sign;
                ++axis_parallel;
                break;
            }
            default:  // anything
                ray = any_ray(random);
        }
        const Expected expected = closed_form(b, ray);
        const auto found = compare_first_hit(s, ray, expected, 1e-9, counts);
        if (!found) continue;
        if (s.inside(ray.origin)) ++from_inside;
        const Vec3 p = found->point;
        CHECK(s.bounds().contains(p, 1e-9));
        CHECK_NEAR(s.normal(p, found->hit), expected.normal, 0.0);  // exact, from the face
    }
    CHECK(counts.hits > 8000);
    CHECK(counts.misses > 3000);
    CHECK(from_inside > 3000);
    CHECK(axis_parallel > 3000);
    CHECK(counts.skipped < 200);
}

TEST(from_inside_every_face_is_the_far_face) {
    const Shape s = parse_shape("12  -1 -2 -3  1 2 3");
    const Vec3 centre{0, 0, 0};
    const Vec3 axes[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const double half[] = {1, 2, 3};
    for (int k = 0; k < 3; ++k) {
        for (const double sign : {-1.0, 1.0}) {
            const auto hit = first_hit(s, {centre, axes[k] * sign});
            CHECK(hit.has_value());
            if (!hit) continue;
            CHECK_NEAR(hit->t, half[k], 1e-15);
            CHECK_NEAR(s.normal(centre + axes[k] * (sign * half[k]), *hit), axes[k] * sign, 0.0);
        }
    }
}

TEST(edges_and_corners_get_a_face_normal) {
    const Shape s = parse_shape("12  0 0 0  1 1 1");
    // Exactly through the edge x = y = 0.
    const auto edge = first_hit(s, {{-1, -1, 0.5}, normalized(Vec3(1, 1, 0))});
    CHECK(edge.has_value());
    if (edge) {
        CHECK_NEAR(edge->t, std::sqrt(2.0), 1e-15);
        const Vec3 n = s.normal({0, 0, 0.5}, *edge);
        CHECK(n == Vec3(-1, 0, 0) || n == Vec3(0, -1, 0));
    }
    // Exactly through the corner at the origin.
    const auto corner = first_hit(s, {{-1, -1, -1}, normalized(Vec3(1, 1, 1))});
    CHECK(corner.has_value());
    if (corner) {
        CHECK_NEAR(corner->t, std::sqrt(3.0), 1e-15);
        const Vec3 n = s.normal({0, 0, 0}, *corner);
        CHECK(n == Vec3(-1, 0, 0) || n == Vec3(0, -1, 0) || n == Vec3(0, 0, -1));
    }
    // Just beside an edge the face is the one hit, even though the point is within rounding
    // of the other face.
    const auto beside = first_hit(s, {{0.5, 1 - 1e-12, 5}, {0, 0, -1}});
    CHECK(beside.has_value());
    if (beside) CHECK_NEAR(s.normal(Vec3(0.5, 1 - 1e-12, 1), *beside), Vec3(0, 0, 1), 0.0);
}

TEST(rays_along_a_face_plane_give_no_nan) {
    const Shape s = parse_shape("12  0 0 0  1 1 1");
    // Parallel to the faces y = const, exactly on y = 1 and on y = 0, from outside and
    // from within the face itself.
    for (const Ray& ray :
         {Ray{{-1, 1, 0.5}, {1, 0, 0}}, Ray{{-1, 0, 0.5}, {1, 0, 0}}, Ray{{0.5, 1, 0.5}, {1, 0, 0}},
          Ray{{0.5, 0, 0.5}, {-1, 0, 0}}, Ray{{0, 0, -1}, {0, 0, 1}}, Ray{{1, 1, 2}, {0, 0, -1}}}) {
        Hit hit;
        if (s.intersect(ray, {1e-9, kInfinity}, hit)) {
            CHECK(std::isfinite(hit.t));
            CHECK(finite(s.normal(ray.at(hit.t), hit)));
            CHECK(s.bounds().contains(ray.at(hit.t), 1e-12));
        }
    }
    // Just outside the slab, parallel to it: a clean miss.
    CHECK(!first_hit(s, {{-1, 1 + 1e-12, 0.5}, {1, 0, 0}}));
    CHECK(!first_hit(s, {{-1, -1e-12, 0.5}, {1, 0, 0}}));
}

TEST(inside_test) {
    const Shape s = parse_shape("12  -1 -2 -3  1 2 3");
    CHECK(s.has_inside());
    CHECK(s.inside({0, 0, 0}));
    CHECK(s.inside({0.99, -1.99, 2.99}));
    CHECK(!s.inside({1.01, 0, 0}));
    CHECK(!s.inside({0, -2.01, 0}));
    CHECK(!s.inside({0, 0, 3.01}));
    CHECK(!s.inside({1, 0, 0}));  // the surface itself is not inside
    CHECK(!s.inside({5, 5, 5}));
}

TEST(bounds_are_the_corners) {
    const Bounds b = parse_shape("12  -1 -2 -3  1 2 3").bounds();
    CHECK_NEAR(b.min, Vec3(-1, -2, -3), 0.0);
    CHECK_NEAR(b.max, Vec3(1, 2, 3), 0.0);
}

TEST(best_distance_so_far_stops_early) {
    const Shape s = parse_shape("12  -1 -1 -1  1 1 1");
    const Ray ray{{0, 0, -10}, {0, 0, 1}};
    Hit hit{123, 7};
    CHECK(!s.intersect(ray, {1e-9, 8.9}, hit));
    CHECK_EQ(hit.t, 123.0);
    CHECK_EQ(hit.part, 7);
    CHECK(s.intersect(ray, {1e-9, 9.1}, hit));
    CHECK_NEAR(hit.t, 9.0, 1e-15);
    // Starting past the near face, the far face is next.
    CHECK(s.intersect(ray, {9.5, kInfinity}, hit));
    CHECK_NEAR(hit.t, 11.0, 1e-15);
    CHECK_NEAR(s.normal(ray.at(hit.t), hit), Vec3(0, 0, 1), 0.0);
}

TEST(read_errors_name_the_field) {
    CHECK_CONTAINS(scene_error(box_scene("0 0 0  1 1 -1")),
                   "test.in:2:11: box max corner must exceed the min corner in every component, "
                   "got z max -1 <= min 0");
    CHECK_CONTAINS(scene_error(box_scene("0 0 0  1 0 1")),
                   "test.in:2:11: box max corner must exceed the min corner in every component, "
                   "got y max 0 <= min 0");
    CHECK_CONTAINS(scene_error(box_scene("2 0 0  1 1 1")),
                   "test.in:2:11: box max corner must exceed the min corner in every component, "
                   "got x max 1 <= min 2");
    CHECK_CONTAINS(scene_error(join(kTestViewer, "12 0 0 0 1 1")),
                   "unexpected end of file: expected box max corner");
    CHECK_EQ(scene_error(box_scene("0 0 0  1 1 1")), std::string());
}
