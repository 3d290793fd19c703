// flat_corners (primitives/flat_corners.h), which bench/embree uses to hand polygons and
// triangles to Embree as fans of triangles: the corners are the written vertices, and the fan
// from the first corner covers every hit of the primitive's own test, concave outlines and
// outlines that cross themselves included.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "check.h"
#include "primitives/flat_corners.h"
#include "primitives/watertight.h"
#include "scene_util.h"

using namespace rt;
using rt_test::Random;

namespace {

std::string polygon_text(const std::vector<Vec3>& vertices) {
    std::ostringstream text;
    text.precision(17);
    text << "11 " << vertices.size();
    for (const Vec3& v : vertices) text << "  " << v.x << ' ' << v.y << ' ' << v.z;
    return text.str();
}

// Whether some triangle of the fan from corners[0] is crossed by the ray (both sides count).
bool fan_crossed(const std::vector<Vec3>& corners, const Ray& ray) {
    const TriangleRay triangle_ray(ray);
    for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
        const SortedTriangle s = SortedTriangle::sort(corners[0], corners[k], corners[k + 1]);
        const Vec3 v[3] = {corners[0], corners[k], corners[k + 1]};
        double t = 0;
        if (triangle_ray.crosses(v[s.order[0]], v[s.order[1]], v[s.order[2]], t)) return true;
    }
    return false;
}

// A star-shaped, concave outline of `points` tips in the plane through `centre` spanned by
// e1, e2 (with a crossing outline when `crossing`: the tips visited two at a time).
std::vector<Vec3> star(Random& random, const Vec3& centre, const Vec3& e1, const Vec3& e2,
                       int points, bool crossing) {
    std::vector<Vec3> outline;
    const int step = crossing ? 2 : 1;
    for (int i = 0; i < 2 * points; ++i) {
        const int k = (i * step) % (2 * points);
        const double angle = 3.14159265358979 * k / points;
        const double r = k % 2 == 0 ? random.uniform(1.0, 2.0) : random.uniform(0.2, 0.6);
        outline.push_back(centre + r * std::cos(angle) * e1 + r * std::sin(angle) * e2);
    }
    return outline;
}

}  // namespace

TEST(a_triangle_gives_its_vertices) {
    const Shape s = rt_test::parse_shape("5  0 0 0  1 0 0  0 1 2");
    const std::vector<Vec3> corners = flat_corners(s);
    CHECK_EQ(corners.size(), std::size_t{3});
    for (const Vec3& v : {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 2}})
        CHECK(std::count(corners.begin(), corners.end(), v) == 1);
}

TEST(other_primitives_have_none) {
    CHECK(flat_corners(rt_test::parse_shape("1  1  0 0 0")).empty());
    CHECK(flat_corners(rt_test::parse_shape("2  0 0 1  0")).empty());
}

TEST(a_polygon_gives_its_vertices_on_its_plane) {
    Random random(11);
    for (int trial = 0; trial < 200; ++trial) {
        const rt_test::Frame f = rt_test::frame_around(random.unit_vector());
        const std::vector<Vec3> outline =
            star(random, random.in_box(5), f.e1, f.e2, 3 + trial % 6, false);
        const std::vector<Vec3> corners = flat_corners(rt_test::parse_shape(polygon_text(outline)));
        CHECK_EQ(corners.size(), outline.size());
        for (std::size_t i = 0; i < corners.size() && i < outline.size(); ++i)
            CHECK(rt_test::near(corners[i], outline[i], 1e-9));
    }
}

TEST(the_fan_covers_every_hit) {
    Random random(12);
    int hits = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const rt_test::Frame f = rt_test::frame_around(random.unit_vector());
        const Vec3 centre = random.in_box(3);
        const std::vector<Vec3> outline =
            star(random, centre, f.e1, f.e2, 3 + trial % 5, trial % 3 == 0);
        const Shape s = rt_test::parse_shape(polygon_text(outline));
        const std::vector<Vec3> corners = flat_corners(s);
        for (int r = 0; r < 50; ++r) {
            // Rays toward points of the polygon's box, from either side of its plane.
            const Vec3 target = centre + random.uniform(-2, 2) * f.e1 + random.uniform(-2, 2) * f.e2;
            const Vec3 origin = target + random.uniform(2, 6) * random.unit_vector();
            const Ray ray{origin, normalized(target - origin)};
            Hit hit;
            if (!s.intersect(ray, {1e-9, kInfinity}, hit)) continue;
            ++hits;
            if (!fan_crossed(corners, ray))
                rt_test::record_failure(__FILE__, __LINE__,
                                        rt_test::join("trial ", trial, " ray ", r,
                                                      ": a hit of the polygon outside its fan"));
        }
    }
    CHECK(hits > 1000);  // 1,567 with these seeds
}
