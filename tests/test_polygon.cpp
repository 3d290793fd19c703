// Polygon (ID 11) against closed forms: stars built in a random plane, whose inside is
// decided here by a fan of triangles from the star's centre (a star is star-shaped about it),
// not by the even-odd crossing count the code uses; and the even-odd rule at known points of
// a self-intersecting pentagram and of an outline with a notch.
#include <cmath>
#include <limits>
#include <vector>

#include "primitives/even_odd.h"
#include "random_rays.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

const std::string kSurface = " 100 1 1 1 0 1 1 0 1\n";
constexpr double kPi = 3.141592653589793;

struct Point2 {
    double x, y;
};

// Scene text for a polygon from world vertices.
std::string polygon_text(const std::vector<Vec3>& vertices) {
    std::string text = join("11 ", vertices.size());
    for (const Vec3& v : vertices) text += join(' ', show(v.x), ' ', show(v.y), ' ', show(v.z));
    return text;
}

// A polygon in the plane z = 0 from 2-D points.
Shape flat_polygon(const std::vector<Point2>& points) {
    std::vector<Vec3> vertices;
    for (const Point2& p : points) vertices.push_back({p.x, p.y, 0});
    return parse_shape(polygon_text(vertices));
}

// Whether a ray straight down onto (x, y) hits a polygon lying in z = 0.
bool hits_at(const Shape& s, double x, double y) {
    return first_hit(s, {{x, y, 5}, {0, 0, -1}}).has_value();
}

double cross2(Point2 a, Point2 b, Point2 c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Distance from p to the segment ab.
double segment_distance(Point2 p, Point2 a, Point2 b) {
    const double dx = b.x - a.x, dy = b.y - a.y;
    double s = ((p.x - a.x) * dx + (p.y - a.y) * dy) / (dx * dx + dy * dy);
    s = s < 0 ? 0 : s > 1 ? 1 : s;
    return std::hypot(p.x - a.x - s * dx, p.y - a.y - s * dy);
}

// Inside a star (counter-clockwise, centred at the origin): in one triangle of its fan.
bool inside_star(const std::vector<Point2>& star, Point2 p) {
    const Point2 centre{0, 0};
    for (std::size_t i = 0; i < star.size(); ++i) {
        const Point2 a = star[i], b = star[(i + 1) % star.size()];
        if (cross2(centre, a, p) >= 0 && cross2(a, b, p) >= 0 && cross2(b, centre, p) >= 0)
            return true;
    }
    return false;
}

std::vector<Point2> star_points(int tips, double outer, double inner, double turn) {
    std::vector<Point2> star;
    for (int i = 0; i < 2 * tips; ++i) {
        const double r = i % 2 ? inner : outer;
        const double angle = turn + kPi * i / tips;
        star.push_back({r * std::cos(angle), r * std::sin(angle)});
    }
    return star;
}

std::string polygon_scene(const std::string& rest) {
    return join(kTestViewer, "11 ", rest, kSurface);
}

}  // namespace

TEST(random_rays_on_random_stars_match_fan_test) {
    Random random(11);
    RayCounts counts;
    int notch_misses = 0;
    for (int i = 0; i < 20000; ++i) {
        const int tips = 3 + static_cast<int>(random.uniform(0, 6));
        const double outer = random.uniform(0.5, 3);
        const std::vector<Point2> star =
            star_points(tips, outer, outer * random.uniform(0.2, 0.8), random.uniform(0, 2 * kPi));
        // A random plane: origin and frame (e1, e2, e3), with the outline counter-clockwise
        // in (e1, e2), so the outward normal is e3; reversed outlines turn it round.
        const Vec3 origin = random.in_box(4);
        const Vec3 e3 = random.unit_vector();
        const Vec3 helper = std::fabs(e3.x) < 0.5 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
        const Vec3 e1 = normalized(cross(e3, helper)), e2 = cross(e3, e1);
        const bool reversed = i % 2 == 1;
        std::vector<Vec3> vertices;
        for (std::size_t k = 0; k < star.size(); ++k) {
            const Point2 p = star[reversed ? star.size() - 1 - k : k];
            vertices.push_back(origin + p.x * e1 + p.y * e2);
        }
        const Shape s = parse_shape(polygon_text(vertices));
        // Aim at points around the star; a tenth of the rays run parallel to the plane,
        // off it, and must miss.
        const Point2 aim{random.uniform(-1.1, 1.1) * outer, random.uniform(-1.1, 1.1) * outer};
        Ray ray;
        ray.origin = random.in_box(10);
        ray.direction = normalized(origin + aim.x * e1 + aim.y * e2 - ray.origin);
        const bool parallel = i % 10 == 0;
        if (parallel) {
            ray.origin = origin + random.uniform(-2, 2) * e1 + random.uniform(-2, 2) * e2 +
                         random.uniform(0.01, 1) * (i % 20 ? e3 : -e3);
            ray.direction = normalized(random.uniform(-1, 1) * e1 + random.uniform(-1, 1) * e2);
        }
        // The closed form: distance to the plane, then the fan test in plane coordinates.
        const double facing = dot(e3, ray.direction);
        ClosedForm expected;
        if (!parallel) {
            const double t = dot(e3, origin - ray.origin) / facing;
            const Vec3 rel = ray.at(t) - origin;
            const Point2 p{dot(rel, e1), dot(rel, e2)};
            for (std::size_t k = 0; k < star.size(); ++k)
                if (segment_distance(p, star[k], star[(k + 1) % star.size()]) < 1e-7)
                    expected.ambiguous = true;
            if (t > 1e-6 && inside_star(star, p)) expected.t = t;
            // Within the tips' circle but outside the star: in a concave notch.
            if (t > 1e-6 && !expected.t && std::hypot(p.x, p.y) < outer) ++notch_misses;
        }
        const auto found = compare_first_hit(s, ray, expected, 1e-9, counts, std::fabs(facing));
        if (!found) continue;
        const Vec3 p = found->point;
        CHECK_NEAR(dot(p - origin, e3), 0.0, 1e-9 * (1 + found->hit.t));
        CHECK_NEAR(s.normal(p, found->hit), reversed ? -e3 : e3, 1e-12);
        CHECK(s.bounds().contains(p, 1e-9));
    }
    CHECK(counts.hits > 4000);
    CHECK(counts.misses > 5000);
    CHECK(notch_misses > 500);
    CHECK(counts.skipped < 100);
}

namespace {

// The even-odd count over every edge, written here as the contract's rule with the code's
// half-open edges and crossing formula, so that the decision must agree to the bit.
bool even_odd_every_edge(const std::vector<Point2>& outline, Point2 p) {
    bool inside = false;
    for (std::size_t i = 0, j = outline.size() - 1; i < outline.size(); j = i++) {
        const Point2 a = outline[i], b = outline[j];
        if ((a.y > p.y) == (b.y > p.y)) continue;
        if (p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y)) inside = !inside;
    }
    return inside;
}

// Outlines with many vertices, which rt files by bands of v: a gear (concave, teeth), a
// random walk (self-intersecting), a comb whose every edge spans the whole height (so fewer
// bands are made), and a circle of 300 points.
std::vector<std::vector<Point2>> many_sided_outlines(Random& random) {
    std::vector<std::vector<Point2>> outlines;
    std::vector<Point2> gear;
    for (int i = 0; i < 96; ++i) {
        const double r = (i / 2) % 2 ? 1.0 : 1.25;
        const double angle = 2 * kPi * i / 96;
        gear.push_back({r * std::cos(angle), r * std::sin(angle)});
    }
    outlines.push_back(gear);
    std::vector<Point2> walk;
    for (int i = 0; i < 200; ++i) walk.push_back({random.uniform(-1, 1), random.uniform(-1, 1)});
    outlines.push_back(walk);
    std::vector<Point2> comb;
    for (int i = 0; i < 200; ++i) comb.push_back({i * 0.01, i % 2 ? 1.0 : 0.0});
    outlines.push_back(comb);
    std::vector<Point2> circle;
    for (int i = 0; i < 300; ++i)
        circle.push_back({std::cos(2 * kPi * i / 300), 3 + std::sin(2 * kPi * i / 300)});
    outlines.push_back(circle);
    // Sixteen vertices, the fewest that are filed.
    outlines.push_back(star_points(8, 2, 0.5, 0.1));
    return outlines;
}

}  // namespace

// The box an outline's test asks first (even_odd.h) refuses only points whose crossing count
// over every edge is even, with the count's own roundings: outlines from 1e-300 to 1e300 in
// size, far from the origin and near it, and points on and a few units in the last place
// around the box's sides and the vertices' v, where the crossings round.
TEST(outline_box_refuses_only_points_the_count_calls_outside) {
    using polygon::Point2;
    Random random(29);
    const double scales[] = {1e-300, 1e-160, 1e-8, 1, 3e5, 1e150, 1e300};
    auto ulps = [](double x, int k) {
        for (; k > 0; --k) x = std::nextafter(x, HUGE_VAL);
        for (; k < 0; ++k) x = std::nextafter(x, -HUGE_VAL);
        return x;
    };
    long points = 0, refused = 0, inside = 0, near_side = 0;
    for (int i = 0; i < 6000; ++i) {
        const double scale = scales[i % 7];
        // A centre up to 1000 sizes away, so that the differences round.
        const Point2 centre{random.uniform(-1000, 1000) * scale * (i % 3 == 0),
                            random.uniform(-1000, 1000) * scale * (i % 5 == 0)};
        const int count = i % 4 == 0 ? 3 : 3 + static_cast<int>(random.uniform(0, 20));
        std::vector<Point2> outline;
        for (int k = 0; k < count; ++k) {
            // Some vertices repeat the first's u or v, so that sides share the box's edge.
            double u = centre.u + random.uniform(-1, 1) * scale;
            double v = centre.v + random.uniform(-1, 1) * scale;
            if (k > 0 && random.uniform() < 0.2) u = outline[0].u;
            if (k > 0 && random.uniform() < 0.2) v = outline[0].v;
            outline.push_back({u, v});
        }
        const polygon::OutlineBox box = polygon::OutlineBox::of(outline);
        double u_min = outline[0].u, u_max = u_min;
        for (const Point2& q : outline)
            u_min = std::fmin(u_min, q.u), u_max = std::fmax(u_max, q.u);
        for (int j = 0; j < 60; ++j) {
            Point2 p;
            const Point2& vertex = outline[static_cast<std::size_t>(random.uniform(0, count))];
            const int k = static_cast<int>(random.uniform(-4, 5));
            switch (j % 4) {
                case 0:  // anywhere about the outline
                    p = {centre.u + random.uniform(-1.2, 1.2) * scale,
                         centre.v + random.uniform(-1.2, 1.2) * scale};
                    break;
                case 1:  // just beside the leftmost or rightmost vertex, at a vertex's v
                    p = {ulps(j % 8 == 1 ? u_min : u_max, k), ulps(vertex.v, k / 2)};
                    break;
                case 2:  // beside the box's u sides, anywhere in v
                    p = {ulps(j % 8 == 2 ? u_min : u_max, k),
                         centre.v + random.uniform(-1, 1) * scale};
                    break;
                default:  // on the box's own sides
                    p = {j % 8 == 3 ? box.u_low : box.u_high, ulps(vertex.v, k)};
                    break;
            }
            bool odd = false;
            for (std::size_t a = 0, b = outline.size() - 1; a < outline.size(); b = a++)
                if (polygon::crosses(outline[a], outline[b], p)) odd = !odd;
            ++points;
            inside += odd;
            if (box.may_hold(p)) continue;
            ++refused;
            near_side += j % 4 != 0;
            CHECK(!odd);
        }
    }
    // The box decides a good part of the points without its edges, close to its sides too.
    CHECK(refused > points / 5);
    CHECK(near_side > points / 10);
    CHECK(inside > points / 20);
    // A NaN is refused, as the count refuses it; an outline too large for a finite margin
    // refuses nothing in u.
    const std::vector<Point2> triangle{{0, 0}, {1, 0}, {0, 1}};
    CHECK(!polygon::OutlineBox::of(triangle).may_hold({std::nan(""), 0.5}));
    CHECK(!polygon::OutlineBox::of(triangle).may_hold({0.2, std::nan("")}));
    const std::vector<Point2> huge{{0, 0}, {1e300, 0}, {0, 1}};
    CHECK(polygon::OutlineBox::of(huge).may_hold({-1e308, 0.5}));
    CHECK(polygon::crossing_margin(1, 1, 0) == HUGE_VAL);
}

TEST(many_sided_outlines_decide_as_the_count_over_every_edge) {
    Random random(1101);
    for (const std::vector<Point2>& outline : many_sided_outlines(random)) {
        const Shape s = flat_polygon(outline);
        double lo_x = outline[0].x, hi_x = lo_x, lo_y = outline[0].y, hi_y = lo_y;
        for (const Point2& q : outline) {
            lo_x = std::fmin(lo_x, q.x), hi_x = std::fmax(hi_x, q.x);
            lo_y = std::fmin(lo_y, q.y), hi_y = std::fmax(hi_y, q.y);
        }
        int differ = 0, inside = 0;
        for (int r = 0; r < 20000; ++r) {
            Point2 p{random.uniform(lo_x - 0.1, hi_x + 0.1),
                     random.uniform(lo_y - 0.1, hi_y + 0.1)};
            // At a vertex's height (the half-open rule), at the extremes, on a vertex.
            const Point2& q = outline[random.next() % outline.size()];
            if (r % 4 == 1) p.y = q.y;
            if (r % 97 == 0) p.y = r % 2 ? lo_y : hi_y;
            if (r % 101 == 0) p = q;
            const bool expected = even_odd_every_edge(outline, p);
            inside += expected ? 1 : 0;
            if (hits_at(s, p.x, p.y) != expected) ++differ;
        }
        CHECK_EQ(differ, 0);
        CHECK(inside > 1000);
    }
}

TEST(even_odd_rule_on_a_pentagram_drawn_with_five_vertices) {
    // The outline crosses itself; by the even-odd rule the five tips are inside and the
    // pentagon in the middle is outside.
    std::vector<Point2> points;
    for (int k = 0; k < 5; ++k) {
        const double angle = kPi / 2 + k * 4 * kPi / 5;
        points.push_back({std::cos(angle), std::sin(angle)});
    }
    const Shape s = flat_polygon(points);
    CHECK(hits_at(s, 0, 0.8));                                                // top tip
    CHECK(hits_at(s, 0.8 * std::cos(kPi / 10), 0.8 * std::sin(kPi / 10)));    // right tip
    CHECK(hits_at(s, 0.8 * std::cos(1.3 * kPi), 0.8 * std::sin(1.3 * kPi)));  // lower left tip
    CHECK(!hits_at(s, 0, -0.45));  // below the notch between the two lower tips
    CHECK(!hits_at(s, 0, 0));      // the middle pentagon
    CHECK(!hits_at(s, 0, 0.2));
    CHECK(!hits_at(s, 0.1, -0.2));
    CHECK(!hits_at(s, 0.5, 0.5));  // between two tips, outside
    CHECK(!hits_at(s, 2, 0));
}

TEST(even_odd_rule_on_a_concave_star) {
    // Five tips of radius 2, notches of radius 0.8, first tip straight up.
    const Shape s = flat_polygon(star_points(5, 2, 0.8, kPi / 2));
    CHECK(hits_at(s, 0, 0));      // centre
    CHECK(hits_at(s, 0, 1.9));    // near the top tip
    CHECK(hits_at(s, 0, -0.7));   // under the bottom notch
    CHECK(!hits_at(s, 0, -0.9));  // just past it, between the lower tips
    CHECK(!hits_at(s, 1.2 * std::cos(kPi / 2 + kPi / 5), 1.2 * std::sin(kPi / 2 + kPi / 5)));
    CHECK(!hits_at(s, 0, 2.1));
}

TEST(even_odd_rule_on_an_outline_with_a_notch) {
    // A square 0..4 with a notch cut down from the top edge between x = 1 and x = 3 to y = 1.
    const Shape s = flat_polygon({{0, 0}, {4, 0}, {4, 4}, {3, 4}, {3, 1}, {1, 1}, {1, 4}, {0, 4}});
    CHECK(hits_at(s, 2, 0.5));    // below the notch
    CHECK(hits_at(s, 0.5, 3));    // left arm
    CHECK(hits_at(s, 3.5, 3.5));  // right arm
    CHECK(!hits_at(s, 2, 3));     // in the notch
    CHECK(!hits_at(s, 2, 1.0001));
    CHECK(hits_at(s, 2, 0.9999));
    CHECK(!hits_at(s, 5, 2));
    // On the line through the notch's bottom corners, where the ray meets vertices.
    CHECK(hits_at(s, 0.5, 1));
    CHECK(hits_at(s, 3.5, 1));
    CHECK(!hits_at(s, -0.5, 1));
    CHECK(!hits_at(s, 4.5, 1));
}

TEST(normal_follows_the_winding) {
    const Shape ccw = flat_polygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    const Shape cw = flat_polygon({{0, 0}, {0, 1}, {1, 1}, {1, 0}});
    CHECK_NEAR(ccw.normal({0.5, 0.5, 0}, Hit{}), Vec3(0, 0, 1), 1e-15);
    CHECK_NEAR(cw.normal({0.5, 0.5, 0}, Hit{}), Vec3(0, 0, -1), 1e-15);
    // A tilted polygon: the plane x + y + z = 1.
    const Shape tilted = parse_shape("11 3  1 0 0  0 1 0  0 0 1");
    CHECK_NEAR(tilted.normal({0.3, 0.3, 0.4}, Hit{}), Vec3(1, 1, 1) / std::sqrt(3.0), 1e-15);
    const auto hit = first_hit(tilted, {{0, 0, 0}, Vec3(1, 1, 1) / std::sqrt(3.0)});
    CHECK(hit.has_value());
    if (hit) CHECK_NEAR(hit->t, 1 / std::sqrt(3.0), 1e-15);
    const Bounds b = tilted.bounds();
    CHECK_NEAR(b.min, Vec3(0, 0, 0), 0.0);
    CHECK_NEAR(b.max, Vec3(1, 1, 1), 0.0);
}

TEST(best_distance_so_far_stops_early) {
    const Shape s = flat_polygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    const Ray ray{{0.5, 0.5, 5}, {0, 0, -1}};
    Hit hit{123, 7};
    CHECK(!s.intersect(ray, {1e-9, 4.9}, hit));
    CHECK_EQ(hit.t, 123.0);
    CHECK(s.intersect(ray, {1e-9, 5.1}, hit));
    CHECK_NEAR(hit.t, 5.0, 1e-15);
}

TEST(nearly_coplanar_vertices_are_accepted) {
    // Off the plane by 1e-6 of the polygon's size: as written with six significant digits.
    CHECK_EQ(scene_error(polygon_scene("4  0 0 0  2 0 0  2 2 0.000002  0 2 0")), std::string());
}

TEST(read_errors_name_the_place) {
    CHECK_CONTAINS(scene_error(polygon_scene("2  0 0 0  1 0 0")),
                   "test.in:2:4: polygon vertex count must be between 3 and 1000000, got 2");
    CHECK_CONTAINS(scene_error(polygon_scene("3.5  0 0 0  1 0 0  0 1 0")),
                   "test.in:2:4: polygon vertex count must be a whole number, got 3.5");
    CHECK_CONTAINS(scene_error(polygon_scene("2000000  0 0 0")),
                   "test.in:2:4: polygon vertex count must be between 3 and 1000000, got 2000000");
    CHECK_CONTAINS(scene_error(polygon_scene("3  0 0 0  1 1 1  2 2 2")),
                   "test.in:2:7: polygon vertices all lie on one line, so they span no plane");
    CHECK_CONTAINS(scene_error(polygon_scene("4  1 1 1  1 1 1  1 1 1  1 1 1")),
                   "test.in:2:7: polygon vertices all lie on one line, so they span no plane");
    // One vertex a line, so that the error's line names the vertex that is off the plane.
    CHECK_CONTAINS(scene_error(join(kTestViewer,
                                    "11 5\n"
                                    "0 0 0\n"
                                    "4 0 0\n"
                                    "4 4 0\n"
                                    "  2 2 0.5\n"
                                    "0 4 0\n",
                                    kSurface)),
                   "test.in:6:3: polygon vertex 3 is not in the plane of the others: it is 0.5 "
                   "away, more than 0.0001 of the polygon's size");
    // A count larger than the vertices given is only an early end of file: nothing is
    // allocated for the count.
    CHECK_CONTAINS(scene_error(join(kTestViewer, "11 1000000  0 0 0  1 0 0  0 1 0")),
                   "unexpected end of file: expected polygon vertex 3");
    // A vertex numbered with three digits, past the room made at once, in the message.
    std::string many = "11 1000000";
    for (int i = 0; i < 123; ++i)
        many += "  " + std::to_string(i % 7) + " " + std::to_string(i % 5) + " 0";
    CHECK_CONTAINS(scene_error(join(kTestViewer, many + " 1 x")),
                   "expected polygon vertex 123 (a number), got 'x'");
    CHECK_EQ(scene_error(polygon_scene("3  0 0 0  1 0 0  0 1 0")), std::string());
}
