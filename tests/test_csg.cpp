// Union (20), intersection (21) and difference (22), against closed forms: an independent
// set-membership oracle on seeded random rays, a lens's focal length, a sphere with a box cut
// out, points of known side, surfaces and normals of nested composites, and reader errors.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "check.h"
#include "rt/optics.h"
#include "rt/render.h"
#include "rt/trace.h"
#include "scene_util.h"

using rt::Vec3;
using rt_test::kTestViewer;
using rt_test::parse_scene;
using rt_test::parse_shape;
using rt_test::scene_error;

namespace {

const std::string kRed = " 100 1 0 0 0 1 1 0 1";
const std::string kGreen = " 100 0 1 0 0 1 1 0 1";
const std::string kBlue = " 100 0 0 1 0 1 1 0 1";

// --- An independent oracle: solids as the test knows them, with their own closed forms. ---

struct Solid {
    bool is_sphere;
    Vec3 a;  // sphere centre, or box min
    Vec3 b;  // (r, r, r) for a sphere, or box max

    std::string text() const {
        return is_sphere ? rt_test::object_text(1, {b.x, a.x, a.y, a.z})
                         : rt_test::object_text(12, {a.x, a.y, a.z, b.x, b.y, b.z});
    }
    bool inside(const Vec3& p) const {
        if (is_sphere) return length_squared(p - a) < b.x * b.x;
        return p.x > a.x && p.x < b.x && p.y > a.y && p.y < b.y && p.z > a.z && p.z < b.z;
    }
    // Every t where the line meets the boundary (some may be outside a box's faces).
    void roots(const rt::Ray& ray, std::vector<double>& out) const {
        if (is_sphere) {
            const Vec3 oc = ray.origin - a;
            const double half_b = dot(oc, ray.direction);
            const double disc = half_b * half_b - (length_squared(oc) - b.x * b.x);
            if (disc < 0) return;
            out.push_back(-half_b - std::sqrt(disc));
            out.push_back(-half_b + std::sqrt(disc));
            return;
        }
        const double o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
        const double d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
        const double lo[3] = {a.x, a.y, a.z}, hi[3] = {b.x, b.y, b.z};
        for (int i = 0; i < 3; ++i) {
            if (d[i] == 0) continue;
            out.push_back((lo[i] - o[i]) / d[i]);
            out.push_back((hi[i] - o[i]) / d[i]);
        }
    }
};

enum class Op { unite = 20, intersect = 21, subtract = 22 };

bool in_set(Op op, bool a, bool b) {
    return op == Op::unite ? a || b : op == Op::intersect ? a && b : a && !b;
}

Solid random_solid(rt_test::Random& random) {
    const Vec3 centre = random.in_box(0.6);
    if (random.uniform() < 0.5) {
        const double r = random.uniform(0.3, 1.0);
        return {true, centre, {r, r, r}};
    }
    const Vec3 half{random.uniform(0.2, 0.9), random.uniform(0.2, 0.9), random.uniform(0.2, 0.9)};
    return {false, centre - half, centre + half};
}

}  // namespace

TEST(random_rays_hit_where_set_membership_changes) {
    rt_test::Random random(2026);
    int compared = 0;
    for (int scene_index = 0; scene_index < 60; ++scene_index) {
        const Op op = static_cast<Op>(20 + static_cast<int>(random.next() % 3));
        const Solid a = random_solid(random), b = random_solid(random);
        const rt::Shape shape = parse_shape(std::to_string(static_cast<int>(op)) + " " + a.text() +
                                            kRed + " " + b.text() + kGreen);
        for (int ray_index = 0; ray_index < 300; ++ray_index) {
            const Vec3 origin = normalized(random.in_box(1)) * 4;
            const rt::Ray ray{origin, normalized(random.in_box(0.8) - origin)};
            std::vector<double> candidates;
            a.roots(ray, candidates);
            b.roots(ray, candidates);
            std::sort(candidates.begin(), candidates.end());
            // The first boundary point where membership of the set changes.
            const double step = 1e-7;
            double expected = rt::kInfinity;
            bool ambiguous = false;
            for (std::size_t i = 0; i < candidates.size(); ++i) {
                const double t = candidates[i];
                if (t <= 1e-3) continue;
                const Vec3 before = ray.at(t - step), after = ray.at(t + step);
                if (in_set(op, a.inside(before), b.inside(before)) ==
                    in_set(op, a.inside(after), b.inside(after)))
                    continue;
                // Two boundaries this close, or a grazing ray, are a toss-up; skip the ray.
                for (std::size_t j = 0; j < candidates.size(); ++j)
                    if (j != i && std::fabs(candidates[j] - t) < 1e-5) ambiguous = true;
                expected = t;
                break;
            }
            if (ambiguous) continue;
            rt::Hit hit;
            const bool found = shape.intersect(ray, {1e-3, rt::kInfinity}, hit);
            CHECK_EQ(found, expected < rt::kInfinity);
            if (!found || expected == rt::kInfinity) continue;
            ++compared;
            CHECK_NEAR(hit.t, expected, 1e-9);
            // The normal points out of the composite: outside just along it, inside against it.
            const Vec3 p = ray.at(hit.t);
            const Vec3 n = shape.normal(p, hit);
            CHECK_NEAR(length(n), 1.0, 1e-12);
            const Vec3 out = p + 1e-6 * n, in = p - 1e-6 * n;
            CHECK(!in_set(op, a.inside(out), b.inside(out)));
            CHECK(in_set(op, a.inside(in), b.inside(in)));
            // The composite's own inside test agrees with the oracle away from the surface.
            CHECK_EQ(shape.inside(ray.at(hit.t + 1e-4)),
                     in_set(op, a.inside(ray.at(hit.t + 1e-4)), b.inside(ray.at(hit.t + 1e-4))));
        }
    }
    CHECK(compared > 5000);
}

TEST(points_of_known_side) {
    // A unit sphere and a box over x > 0 overlapping half of it.
    const std::string a = "1 1 0 0 0" + kRed, b = "12 0 -2 -2 2 2 2" + kGreen;
    const rt::Shape u = parse_shape("20 " + a + " " + b);
    const rt::Shape i = parse_shape("21 " + a + " " + b);
    const rt::Shape d = parse_shape("22 " + a + " " + b);
    const Vec3 left_in_sphere{-0.5, 0, 0}, right_in_both{0.5, 0, 0}, box_only{1.5, 1.5, 0},
        neither{-1.5, 0, 0};
    CHECK(u.inside(left_in_sphere) && u.inside(right_in_both) && u.inside(box_only));
    CHECK(!u.inside(neither));
    CHECK(!i.inside(left_in_sphere) && i.inside(right_in_both) && !i.inside(box_only));
    CHECK(d.inside(left_in_sphere) && !d.inside(right_in_both) && !d.inside(box_only));
    CHECK(!i.inside(neither) && !d.inside(neither));
    CHECK(u.has_inside() && i.has_inside() && d.has_inside());
}

TEST(sphere_with_a_box_cut_out) {
    // The octant x, y, z > 0 of a unit sphere is cut away by a box.
    const rt::Scene scene = parse_scene(std::string(kTestViewer) + "22  1 1 0 0 0" + kRed +
                                        "  12 0 0 0 2 2 2" + kGreen);
    rt::Tracer tracer(scene, {});
    const rt::Object& object = scene.objects.at(0);
    // Straight down onto the cut: the sphere's cap there is gone, and the box's face z = 0
    // (inside the sphere) is what is seen, with the box's surface and its normal turned
    // around to point out of the composite.
    {
        const rt::Ray ray{{0.5, 0.5, 5}, {0, 0, -1}};
        const auto found = tracer.closest_hit(ray);
        CHECK(found.has_value());
        CHECK_NEAR(found->hit.t, 5.0, 1e-12);
        CHECK_NEAR(object.shape.normal(ray.at(found->hit.t), found->hit), Vec3(0, 0, 1), 1e-12);
        CHECK_NEAR(object.surface_at(found->hit).at({}).colour, rt::Spectrum(0, 1, 0), 0);
        CHECK(object.surface == nullptr);  // a composite has no surface of its own
    }
    // Beside the cut the sphere is whole: z = sqrt(1 - x^2 - y^2).
    {
        const rt::Ray ray{{-0.5, 0.5, 5}, {0, 0, -1}};
        const auto found = tracer.closest_hit(ray);
        CHECK(found.has_value());
        CHECK_NEAR(found->hit.t, 5 - std::sqrt(0.5), 1e-12);
        const Vec3 p = ray.at(found->hit.t);
        CHECK_NEAR(object.shape.normal(p, found->hit), p, 1e-12);
        CHECK_NEAR(object.surface_at(found->hit).at({}).colour, rt::Spectrum(1, 0, 0), 0);
    }
    // Through the cut's corner region along x: the face x = 0 of the box, normal -x.
    {
        const rt::Ray ray{{5, 0.3, 0.4}, {-1, 0, 0}};
        const auto found = tracer.closest_hit(ray);
        CHECK(found.has_value());
        CHECK_NEAR(found->hit.t, 5.0, 1e-12);
        CHECK_NEAR(object.shape.normal(ray.at(5), found->hit), Vec3(1, 0, 0), 1e-12);
    }
    // Bounds: a difference is bounded by A.
    const rt::Bounds box = object.shape.bounds();
    CHECK_NEAR(box.min, Vec3(-1, -1, -1), 0);
    CHECK_NEAR(box.max, Vec3(1, 1, 1), 0);
}

TEST(a_lens_focuses_paraxial_rays_at_its_back_focal_distance) {
    // A symmetric biconvex lens: two spheres of radius R whose centres are 2c apart; its
    // thickness is d = 2(R - c). Thick-lens optics in air gives the focal length
    // 1/f = (n - 1)(2/R - (n - 1) d / (n R^2)) and the back focal distance
    // BFD = f (1 - (n - 1) d / (n R)), measured from the back vertex.
    const double R = 2, c = 1.7, n = 1.5;
    const double d = 2 * (R - c);
    const double f = 1 / ((n - 1) * (2 / R - (n - 1) * d / (n * R * R)));
    const double bfd = f * (1 - (n - 1) * d / (n * R));
    const std::string glass = " 100 1 1 1 0 1 0 1 " + std::to_string(n);
    const rt::Scene scene = parse_scene(std::string(kTestViewer) + "21  1 2 0 0 -1.7" + glass +
                                        "  1 2 0 0 1.7" + glass);
    rt::Tracer tracer(scene, {});
    const rt::Object& lens = scene.objects.at(0);
    for (const double h : {1e-4, 2e-4, 5e-4}) {
        rt::Ray ray{{h, 0, 5}, {0, 0, -1}};
        // Front face: on the sphere centred at -c, entering.
        const auto front = tracer.closest_hit(ray);
        CHECK(front.has_value());
        const Vec3 p1 = ray.at(front->hit.t);
        CHECK_NEAR(p1.z, -c + std::sqrt(R * R - h * h), 1e-12);
        const Vec3 n1 = lens.shape.normal(p1, front->hit);
        CHECK_NEAR(n1, normalized(p1 - Vec3(0, 0, -c)), 1e-12);
        CHECK(dot(n1, ray.direction) < 0);  // entering the composite
        const auto inside = rt::refract(ray.direction, n1, 1 / n);
        CHECK(inside.has_value());
        ray = {p1, *inside};
        // Back face: on the sphere centred at +c, and the ray is leaving.
        const auto back = tracer.closest_hit(ray);
        CHECK(back.has_value());
        const Vec3 p2 = ray.at(back->hit.t);
        CHECK_NEAR(length(p2 - Vec3(0, 0, c)), R, 1e-12);
        const Vec3 n2 = lens.shape.normal(p2, back->hit);
        CHECK(dot(n2, ray.direction) > 0);  // leaving the composite
        const auto out = rt::refract(ray.direction, -n2, n);
        CHECK(out.has_value());
        // Where the emerging ray crosses the axis, measured from the back vertex at z = c - R.
        const double s = -p2.x / out->x;
        const double focus_z = p2.z + s * out->z;
        CHECK_NEAR((c - R) - focus_z, bfd, bfd * 1e-6);
    }
}

TEST(a_plane_is_a_half_space) {
    // A unit sphere cut by the plane z = 0, keeping z < 0: a hemisphere with a flat top.
    const rt::Shape hemisphere = parse_shape("21  1 1 0 0 0" + kRed + "  2 0 0 0 1" + kBlue);
    rt::Hit hit;
    const rt::Ray down{{0.3, 0.2, 5}, {0, 0, -1}};
    CHECK(hemisphere.intersect(down, {1e-9, rt::kInfinity}, hit));
    CHECK_NEAR(hit.t, 5.0, 1e-12);
    CHECK_NEAR(hemisphere.normal(down.at(hit.t), hit), Vec3(0, 0, 1), 0);
    const rt::Ray up{{0.3, 0.2, -5}, {0, 0, 1}};
    CHECK(hemisphere.intersect(up, {1e-9, rt::kInfinity}, hit));
    CHECK_NEAR(hit.t, 5 - std::sqrt(1 - 0.13), 1e-12);
    // Bounded by the sphere, not by the infinite plane.
    CHECK_NEAR(hemisphere.bounds().min, Vec3(-1, -1, -1), 0);
    CHECK_NEAR(hemisphere.bounds().max, Vec3(1, 1, 1), 0);
    // A union with a plane is unbounded.
    CHECK(std::isinf(parse_shape("20  1 1 0 0 0" + kRed + "  2 0 0 0 1" + kBlue).bounds().max.x));
}

TEST(nested_composites_report_the_operand_surface_and_normal) {
    // A die: a box minus a union of two pips, nested inside an affine that moves it by +10 in
    // x. The pips are spheres centred on the face z = 1.
    const std::string pips = "20  1 0.3 -0.5 0 1" + kGreen + "  1 0.3 0.5 0 1" + kBlue;
    const std::string die = "22  12 -1 -1 -1 1 1 1" + kRed + "  " + pips;
    const rt::Scene scene =
        parse_scene(std::string(kTestViewer) + "7  10 0 0  1 0 0  0 1 0  0 0 1  " + die +
                    "\n1 0.1  0 0 -50" + kRed);
    CHECK_EQ(scene.objects.size(), std::size_t{2});  // no surface was read after the affine
    const rt::Object& object = scene.objects.at(0);
    rt::Tracer tracer(scene, {});
    for (const double x : {-0.5, 0.5}) {
        // Straight down into a pip's centre: the pit's floor at depth 0.3, normal +z (the
        // pip sphere's normal turned around), in the pip's colour.
        const rt::Ray ray{{10 + x, 0, 5}, {0, 0, -1}};
        const auto found = tracer.closest_hit(ray);
        CHECK(found.has_value());
        CHECK_NEAR(found->hit.t, 4.3, 1e-12);
        CHECK_NEAR(object.shape.normal(ray.at(found->hit.t), found->hit), Vec3(0, 0, 1), 1e-12);
        CHECK_NEAR(object.surface_at(found->hit).at({}).colour,
                   x < 0 ? rt::Spectrum(0, 1, 0) : rt::Spectrum(0, 0, 1), 0);
        // Off the pips, the die's face in the box's colour.
        const rt::Ray face{{10, 0.6, 5}, {0, 0, -1}};
        const auto on_face = tracer.closest_hit(face);
        CHECK(on_face.has_value());
        CHECK_NEAR(on_face->hit.t, 4.0, 1e-12);
        CHECK_NEAR(object.surface_at(on_face->hit).at({}).colour, rt::Spectrum(1, 0, 0), 0);
    }
    // A ray that starts inside a pit and goes out again leaves through the top.
    const rt::Ray out{{9.5, 0, 0.8}, {0, 0, 1}};
    CHECK(!tracer.closest_hit(out).has_value() || tracer.closest_hit(out)->object != &object);
}

TEST(a_render_through_a_composite_matches_the_linear_scan) {
    const std::string scene_text =
        "102  0 0 6  0 0 0  1 0 0  0 0.75 0  32 24\n101 3 4 6 1 1 1\n103 0.1 0.1 0.1\n"
        "22  1 1 0 0 0  100 0.8 0.3 0.3 0.3 20 0.6 0.2 1.5  12 0 0 0 2 2 2  100 0.2 0.8 0.2 0.2 "
        "10 0.8 0 1\n"
        "21  1 1.5 -1 0 -0.8  100 0.9 0.9 1 0.1 20 0.1 0.9 1.5  1 1.5 -1 0 0.8  106\n"
        "2 -1.5 0 1 0  100 0.5 0.5 0.5 0 1 1 0 1\n";
    // 106 inside a composite takes the default surface like anywhere else; set one first.
    const std::string with_default = "105 100 0.9 0.9 1 0.1 20 0.1 0.9 1.5\n" + scene_text;
    const rt::Scene scene = parse_scene(with_default);
    rt::RenderOptions linear;
    linear.accelerate = false;
    const rt::Raster a = rt::render(scene, {}), b = rt::render(scene, linear);
    bool same = true;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) same = same && a.at(x, y) == b.at(x, y);
    CHECK(same);
}

TEST(reader_errors_name_the_operand) {
    const std::string v = kTestViewer;
    CHECK_CONTAINS(scene_error(v + "20  3 0 0 0 0 0 1 1" + kRed + "  1 1 0 0 0" + kRed),
                   "test.in:2:5: union operand A is a disk (3), which has no inside");
    CHECK_CONTAINS(scene_error(v + "21  1 1 0 0 0" + kRed + "  5 0 0 0 1 0 0 0 1 0" + kRed),
                   "test.in:2:36: intersection operand B is a triangle (5), which has no inside");
    CHECK_CONTAINS(scene_error(v + "22  7 0 0 0 1 0 0 0 1 0 0 0 1  3 0 0 0 0 0 1 1" + kRed +
                               " 1 1 0 0 0" + kRed),
                   "test.in:2:5: difference operand A is an affine (7), which has no inside");
    // Composites nest like affines, and count toward the same limit.
    std::string deep = v;
    for (int i = 0; i < 40; ++i) deep += "20 ";
    CHECK_CONTAINS(scene_error(deep + "1 1 0 0 0" + kRed), "objects nested more than 32 deep");
    // End of file inside an operand.
    CHECK_CONTAINS(scene_error(v + "20  1 1 0 0 0" + kRed),
                   "unexpected end of file: expected union operand B ID");
    // A composite at the top level reads no surface after it: the next number is an object.
    CHECK_EQ(scene_error(v + "20  1 1 0 0 0" + kRed + "  1 1 2 0 0" + kRed + "\n103 1 1 1"), "");
}

TEST(a_quadric_operand_is_its_whole_solid_not_only_its_clipped_surface) {
    // A = unit sphere; B = the half-space z < 0 written as the quadric f = z (2I = 1), whose
    // surface is clipped to a small box around the origin. A ∩ B is the lower hemisphere,
    // but its flat face shows only inside B's clip box.
    const std::string half_space = "13  0 0 0 0 0 0  0 0 0.5 0  -0.1 -0.1 -0.1  0.1 0.1 0.1";
    const rt::Scene scene =
        parse_scene(std::string(kTestViewer) + "21  1 1 0 0 0" + kRed + "  " + half_space + kBlue);
    rt::Tracer tracer(scene, {});
    const rt::Object& object = scene.objects.at(0);
    // Down through the invisible part of the face: the ray crosses into B where nothing is
    // drawn and meets the sphere's bottom from inside.
    const rt::Ray ray{{0.5, 0, 5}, {0, 0, -1}};
    const auto found = tracer.closest_hit(ray);
    CHECK(found.has_value());
    CHECK_NEAR(found->hit.t, 5 + std::sqrt(0.75), 1e-12);
    const Vec3 p = ray.at(found->hit.t);
    CHECK_NEAR(object.shape.normal(p, found->hit), p, 1e-12);  // the sphere's, pointing out
    CHECK_NEAR(object.surface_at(found->hit).at({}).colour, rt::Spectrum(1, 0, 0), 0);
    // Down through the visible part: the flat face, B's surface, normal +z.
    const rt::Ray centre{{0.05, 0, 5}, {0, 0, -1}};
    const auto on_face = tracer.closest_hit(centre);
    CHECK(on_face.has_value());
    CHECK_NEAR(on_face->hit.t, 5.0, 1e-12);
    CHECK_NEAR(object.shape.normal(centre.at(5), on_face->hit), Vec3(0, 0, 1), 1e-12);
    CHECK_NEAR(object.surface_at(on_face->hit).at({}).colour, rt::Spectrum(0, 0, 1), 0);
    // The composite's box is the sphere's: B's solid is not clipped, even though its
    // surface's box is small, so the hierarchy keeps every hit (the linear scan agrees).
    CHECK_NEAR(object.shape.bounds().min, Vec3(-1, -1, -1), 0);
    CHECK_NEAR(object.shape.bounds().max, Vec3(1, 1, 1), 0);
    rt::RenderOptions linear;
    linear.accelerate = false;
    const auto slow = rt::Tracer(scene, linear).closest_hit(ray);
    CHECK(slow.has_value() && slow->hit.t == found->hit.t);
}

TEST(a_quadric_solid_is_bounded_only_when_it_is_an_ellipsoid_interior) {
    const std::string clip = "  -10 -10 -10  10 10 10";
    // x² + y² + z² − 1: the unit ball.
    const rt::Shape ball = parse_shape("13  1 1 1 0 0 0 0 0 0 -1" + clip);
    CHECK_NEAR(ball.solid_bounds().min, Vec3(-1, -1, -1), 1e-9);
    CHECK_NEAR(ball.solid_bounds().max, Vec3(1, 1, 1), 1e-9);
    // 1 − x² − y² − z²: everything outside the unit sphere.
    CHECK(std::isinf(parse_shape("13  -1 -1 -1 0 0 0 0 0 0 1" + clip).solid_bounds().max.x));
    // A cylinder x² + y² − 1: unbounded along z.
    CHECK(std::isinf(parse_shape("13  1 1 0 0 0 0 0 0 0 -1" + clip).solid_bounds().max.z));
    // An ellipsoid clipped to half: its surface box is cut, its solid box is not.
    const rt::Shape half = parse_shape("13  1 1 1 0 0 0 0 0 0 -1  -2 -2 0  2 2 2");
    CHECK_NEAR(half.bounds().min.z, 0.0, 1e-9);
    CHECK_NEAR(half.solid_bounds().min.z, -1.0, 1e-9);
}
