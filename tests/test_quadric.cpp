// Quadric (ID 13) against closed forms: the sphere's and the cylinder's geometric distance,
// the planes of a plane pair, the paraboloid along its axis, rays along a cone's asymptote;
// and, for every form, against a reference that solves the quadratic in long double straight
// from the scene's coefficients (no recentring, no shift along the ray). Points on the
// surfaces come from parametric forms, so rays leaving the surface are checked for acne.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "random_rays.h"
#include "rt/trace.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

using Real = long double;

// A quadric's sixteen numbers, with f and ∇f evaluated in long double.
struct Spec {
    std::array<double, 10> k{};  // A B C D E F G H I J
    Vec3 min{-1e3, -1e3, -1e3}, max{1e3, 1e3, 1e3};

    Shape shape() const {
        return parse_shape(object_text(13, {k[0], k[1], k[2], k[3], k[4], k[5], k[6], k[7], k[8],
                                            k[9], min.x, min.y, min.z, max.x, max.y, max.z}));
    }
    Real f(const Vec3& p) const {
        const Real x = p.x, y = p.y, z = p.z;
        return k[0] * x * x + k[1] * y * y + k[2] * z * z + 2 * (k[3] * x * y + k[4] * x * z) +
               2 * (k[5] * y * z + k[6] * x + k[7] * y + k[8] * z) + k[9];
    }
    Vec3 gradient(const Vec3& p) const {
        const Real x = p.x, y = p.y, z = p.z;
        return {static_cast<double>(k[0] * x + k[3] * y + k[4] * z + k[6]),
                static_cast<double>(k[3] * x + k[1] * y + k[5] * z + k[7]),
                static_cast<double>(k[4] * x + k[5] * y + k[2] * z + k[8])};
    }
    bool in_box(const Vec3& p, double slack) const { return Bounds{min, max}.contains(p, slack); }
};

// A rotation, as its three columns.
struct Rotation {
    Vec3 c0{1, 0, 0}, c1{0, 1, 0}, c2{0, 0, 1};
    Vec3 operator*(const Vec3& v) const { return v.x * c0 + v.y * c1 + v.z * c2; }
};

Rotation random_rotation(Random& random) {
    const Frame frame = frame_around(random.unit_vector());
    return {frame.e1, frame.e2, frame.e3};
}

// The quadric y·diag(q)·y + 2 g·y + j = 0 in a local frame whose point y appears in the world
// at centre + R y: the world's coefficients, worked out in long double.
Spec place(const Vec3& q, const Vec3& g, double j, const Vec3& centre, const Rotation& r = {}) {
    const Vec3 col[3] = {r.c0, r.c1, r.c2};
    Real m[3][3] = {};  // R diag(q) Rᵀ
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
            for (int i = 0; i < 3; ++i) m[a][b] += Real(col[i][a]) * q[i] * col[i][b];
    Real gw[3];  // R g − Q c
    const Vec3 rg = r * g;
    for (int a = 0; a < 3; ++a) {
        gw[a] = rg[a];
        for (int b = 0; b < 3; ++b) gw[a] -= m[a][b] * centre[b];
    }
    // J = cᵀQc − 2 (Rg)·c + j
    Real jw = j;
    for (int a = 0; a < 3; ++a) {
        jw -= 2 * Real(rg[a]) * centre[a];
        for (int b = 0; b < 3; ++b) jw += Real(centre[a]) * m[a][b] * centre[b];
    }
    Spec s;
    s.k = {double(m[0][0]), double(m[1][1]), double(m[2][2]), double(m[0][1]), double(m[0][2]),
           double(m[1][2]), double(gw[0]),   double(gw[1]),   double(gw[2]),   double(jw)};
    return s;
}

// The reference: the roots of f along the ray, in ascending order, in long double from the
// coefficients as written.
struct ReferenceRoots {
    double t[2] = {};
    int count = 0;
};

ReferenceRoots reference_roots(const Spec& s, const Ray& ray) {
    const Real o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
    const Real d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
    const Real q[3][3] = {
        {s.k[0], s.k[3], s.k[4]}, {s.k[3], s.k[1], s.k[5]}, {s.k[4], s.k[5], s.k[2]}};
    const Real g[3] = {s.k[6], s.k[7], s.k[8]};
    Real a = 0, b = 0, c = s.k[9];
    for (int i = 0; i < 3; ++i) {
        b += d[i] * g[i];
        c += 2 * o[i] * g[i];
        for (int j = 0; j < 3; ++j) {
            a += d[i] * q[i][j] * d[j];
            b += d[i] * q[i][j] * o[j];
            c += o[i] * q[i][j] * o[j];
        }
    }
    const Real disc = b * b - a * c;
    ReferenceRoots roots;
    if (disc < 0) return roots;
    if (a == 0) {
        if (b != 0) roots = {{double(-c / (2 * b)), 0}, 1};
        return roots;
    }
    const Real qq = -(b + std::copysign(std::sqrt(disc), b));
    const double first = double(qq / a), second = qq != 0 ? double(c / qq) : first;
    return {{std::min(first, second), std::max(first, second)}, 2};
}

// The nearest root beyond t_min that lies in the clip box.
std::optional<double> reference_hit(const Spec& s, const Ray& ray, double t_min = 1e-9) {
    const ReferenceRoots roots = reference_roots(s, ray);
    for (int i = 0; i < roots.count; ++i)
        if (roots.t[i] > t_min && s.in_box(ray.at(roots.t[i]), 1e-9)) return roots.t[i];
    return std::nullopt;
}

// The hit's distance and normal against the reference; returns whether it hit.
struct Tally {
    int hits = 0, misses = 0, disagreements = 0;
};

void check_against_reference(const Spec& spec, const Shape& shape, const Ray& ray, Tally& tally,
                             double tolerance = 1e-9) {
    const auto expected = reference_hit(spec, ray);
    const auto hit = first_hit(shape, ray);
    if (hit.has_value() != expected.has_value()) {
        // Allowed only where the answer hangs on rounding: a grazing ray, or a root at the
        // very edge of the clip box.
        ++tally.disagreements;
        return;
    }
    if (!hit) {
        ++tally.misses;
        return;
    }
    ++tally.hits;
    CHECK_NEAR(hit->t, *expected, tolerance * (1 + *expected));
    const Vec3 p = ray.at(hit->t);
    CHECK_NEAR(shape.normal(p, *hit), normalized(spec.gradient(p)), 1e-7);
    CHECK(shape.bounds().contains(p, 1e-9 * (1 + max_abs_component(p))));
}

// Rays that start in a box of size `spread` about `centre`, most aimed near it.
Ray random_ray(Random& random, const Vec3& centre, double spread, int i) {
    const Vec3 o = centre + random.in_box(spread);
    const Vec3 aim = centre + random.in_box(spread * 0.3);
    return {o, i % 4 ? normalized(aim - o) : random.unit_vector()};
}

}  // namespace

TEST(sphere_as_quadric_matches_sphere_formula) {
    Random random(13);
    RayCounts counts;
    for (int i = 0; i < 20000; ++i) {
        const double r = random.uniform(0.1, 3);
        const Vec3 c = random.in_box(5);
        const Spec spec = place({1, 1, 1}, {}, -r * r, c);
        const Shape shape = spec.shape();
        const Ray ray = ray_at_ball(random, c, r, i);
        const auto found =
            compare_first_hit(shape, ray, {sphere_distance(c, r, ray)}, 1e-9, counts);
        if (!found) continue;
        const Vec3 p = found->point;
        CHECK_NEAR(shape.normal(p, found->hit), (p - c) / r, 1e-9);
        CHECK(shape.bounds().contains(p, 1e-9));
    }
    CHECK(counts.hits > 5000);
    CHECK(counts.misses > 5000);
}

TEST(cylinder_as_quadric_matches_closed_form) {
    Random random(14);
    RayCounts counts;
    for (int i = 0; i < 20000; ++i) {
        const double r = random.uniform(0.1, 2);
        const Vec3 c = random.in_box(3);
        const Rotation rot = random_rotation(random);
        const Vec3 axis = rot.c2;
        // x² + y² − r² in the local frame: no z.
        const Spec spec = place({1, 1, 0}, {}, -r * r, c, rot);
        const Shape shape = spec.shape();
        const Ray ray = random_ray(random, c, 6, i);
        // The closed form: the circle in the plane across the axis.
        const Vec3 oc = ray.origin - c;
        const Vec3 o_across = oc - dot(oc, axis) * axis;
        const Vec3 d_across = ray.direction - dot(ray.direction, axis) * axis;
        const double a = length_squared(d_across);
        ClosedForm expected;
        if (a > 1e-12) {
            const double along = -dot(o_across, d_across) / a;
            const double miss2 = length_squared(o_across + along * d_across);
            if (miss2 <= r * r) {
                const double half = std::sqrt((r * r - miss2) / a);
                if (along - half > 1e-9)
                    expected.t = along - half;
                else if (along + half > 1e-9)
                    expected.t = along + half;
            }
        }
        const auto found = compare_first_hit(shape, ray, expected, 1e-9, counts);
        if (!found) continue;
        const Vec3 p = found->point;
        const Vec3 radial = (p - c) - dot(p - c, axis) * axis;
        CHECK_NEAR(shape.normal(p, found->hit), radial / r, 1e-8);
    }
    CHECK(counts.hits > 5000);
}

TEST(every_form_matches_the_long_double_reference) {
    struct Form {
        const char* name;
        Vec3 q, g;
        double j;
    };
    const Form forms[] = {
        {"ellipsoid", {1, 4, 0.25}, {}, -1},
        {"cone", {1, 1, -0.5}, {}, 0},
        {"paraboloid", {1, 1, 0}, {0, 0, -0.5}, 0},
        {"hyperboloid of one sheet", {1, 1, -1}, {}, -1},
        {"hyperboloid of two sheets", {1, 1, -1}, {}, 1},
        {"hyperbolic paraboloid", {1, -1, 0}, {0, 0, -0.5}, 0},
        {"elliptic cylinder", {1, 9, 0}, {}, -1},
        {"parabolic cylinder", {1, 0, 0}, {0, 0, -0.5}, 0},
        {"plane pair", {1, 0, 0}, {}, -1},
        {"intersecting planes", {1, -4, 0}, {}, 0},
        {"inside-out sphere", {-1, -1, -1}, {}, 1},
    };
    Random random(15);
    for (const Form& form : forms) {
        Tally tally;
        for (int i = 0; i < 4000; ++i) {
            const Vec3 c = random.in_box(3);
            Spec spec = place(form.q, form.g, form.j, c, random_rotation(random));
            // Every other quadric clipped to a box about its centre, so rays meet clipped roots.
            if (i % 2) {
                spec.min = c - Vec3{1.5, 1.5, 1.5} + random.in_box(0.5);
                spec.max = c + Vec3{1.5, 1.5, 1.5} + random.in_box(0.5);
            }
            check_against_reference(spec, spec.shape(), random_ray(random, c, 6, i), tally);
        }
        if (tally.hits < 600 || tally.disagreements > 4)
            record_failure(__FILE__, __LINE__,
                           join(form.name, ": ", tally.hits, " hits, ", tally.misses, " misses, ",
                                tally.disagreements, " disagreements"));
    }
}

TEST(paraboloid_along_its_axis_is_linear) {
    // f = x² + y² − z: rays parallel to the axis meet it once, at z = x² + y².
    const Spec spec = place({1, 1, 0}, {0, 0, -0.5}, 0, {});
    const Shape shape = spec.shape();
    Random random(16);
    for (int i = 0; i < 1000; ++i) {
        const double x = random.uniform(-3, 3), y = random.uniform(-3, 3);
        const double z = x * x + y * y;
        // From below (outside), going up: in through the surface.
        auto hit = first_hit(shape, {{x, y, -5}, {0, 0, 1}});
        CHECK(hit.has_value());
        if (hit) CHECK_NEAR(hit->t, z + 5, 1e-12 * (1 + z));
        // From above (inside), going down: out through it; going up: nothing.
        hit = first_hit(shape, {{x, y, 30}, {0, 0, -1}});
        CHECK(hit.has_value());
        if (hit) CHECK_NEAR(hit->t, 30 - z, 1e-12 * 30);
        CHECK(!first_hit(shape, {{x, y, 30}, {0, 0, 1}}));
    }
    // Tilted and moved, rays along the axis (a is zero only up to rounding).
    for (int i = 0; i < 1000; ++i) {
        const Rotation rot = random_rotation(random);
        const Vec3 c = random.in_box(5);
        const Spec tilted = place({1, 1, 0}, {0, 0, -0.5}, 0, c, rot);
        const double x = random.uniform(-3, 3), y = random.uniform(-3, 3);
        const double z = x * x + y * y;
        const Ray ray{c + rot * Vec3{x, y, -5}, rot.c2};
        const auto hit = first_hit(tilted.shape(), ray);
        CHECK(hit.has_value());
        if (hit) CHECK_NEAR(hit->t, z + 5, 1e-9 * (1 + z));
    }
}

TEST(rays_along_a_cone_asymptote) {
    // x² + y² − z² = 0; the direction (1, 0, 1)/√2 runs along the cone (a = 0 exactly).
    const Spec cone = place({1, 1, -1}, {}, 0, {});
    const Vec3 along = normalized(Vec3{1, 0, 1});
    // Beside the cone, from (−1, 0, 0): (u − 1)² = u² at u = 1/2, the point (−0.5, 0, 0.5).
    auto hit = first_hit(cone.shape(), {{-1, 0, 0}, along});
    CHECK(hit.has_value());
    if (hit) CHECK_NEAR(hit->t, std::sqrt(0.5), 1e-15);
    if (hit)
        CHECK_NEAR(cone.shape().normal({-0.5, 0, 0.5}, *hit), normalized(Vec3{-1, 0, -1}), 1e-15);
    // From (1, 0, 0) the crossing is behind; parallel to a generator off the cone: none.
    CHECK(!first_hit(cone.shape(), {{1, 0, 0}, along}));
    CHECK(!first_hit(cone.shape(), {{0, 1, 0}, along}));
    // The hyperboloid x² + y² − z² = 1 from (−2, 0, 0): 4 − 4u = 1 at u = 3/4.
    const Spec one_sheet = place({1, 1, -1}, {}, -1, {});
    hit = first_hit(one_sheet.shape(), {{-2, 0, 0}, along});
    CHECK(hit.has_value());
    if (hit) CHECK_NEAR(hit->t, 0.75 * std::sqrt(2.0), 1e-15);
    // From its centre along the asymptote it is never met.
    CHECK(!first_hit(one_sheet.shape(), {{0, 0, 0}, along}));
    // Nearly along the asymptote, tilted and moved: the reference agrees.
    Random random(17);
    Tally tally;
    for (int i = 0; i < 4000; ++i) {
        const Rotation rot = random_rotation(random);
        const Vec3 c = random.in_box(3);
        const Spec spec = place({1, 1, -1}, {}, i % 2 ? -1.0 : 0.0, c, rot);
        const double phi = random.uniform(0, 6.283185307179586);
        const Vec3 generator = rot * normalized(Vec3{std::cos(phi), std::sin(phi), 1});
        const Vec3 d =
            normalized(generator + random.in_box(std::pow(10.0, -random.uniform(3, 12))));
        check_against_reference(spec, spec.shape(), {c + random.in_box(2), d}, tally, 1e-7);
    }
    CHECK(tally.hits > 1000);
    CHECK(tally.disagreements <= 4);
}

TEST(plane_pairs) {
    // x² − 1 = 0: the planes x = ±1; the solid is the slab between them.
    Spec slab = place({1, 0, 0}, {}, -1, {});
    // xy = 0 (D = 1/2): the planes x = 0 and y = 0.
    Spec cross_planes;
    cross_planes.k = {0, 0, 0, 0.5, 0, 0, 0, 0, 0, 0};
    // Rays nearly along a plane meet it far away: a clip box that keeps them all.
    slab.min = cross_planes.min = {-1e300, -1e300, -1e300};
    slab.max = cross_planes.max = {1e300, 1e300, 1e300};
    Random random(18);
    for (int i = 0; i < 5000; ++i) {
        const Ray ray{random.in_box(4), random.unit_vector()};
        // The nearest positive distance to the planes (infinity: none).
        double expected = kInfinity;
        for (double x : {-1.0, 1.0}) {
            const double t = (x - ray.origin.x) / ray.direction.x;
            if (t > 1e-9) expected = std::min(expected, t);
        }
        auto hit = first_hit(slab.shape(), ray);
        CHECK_EQ(hit.has_value(), expected < kInfinity);
        if (hit && expected < kInfinity) {
            CHECK_NEAR(hit->t, expected, 1e-9 * (1 + expected));
            const Vec3 p = ray.at(hit->t);
            CHECK_NEAR(slab.shape().normal(p, *hit), Vec3(p.x > 0 ? 1 : -1, 0, 0), 1e-12);
        }
        expected = kInfinity;
        for (int axis = 0; axis < 2; ++axis) {
            const double t = -ray.origin[axis] / ray.direction[axis];
            if (t > 1e-9) expected = std::min(expected, t);
        }
        hit = first_hit(cross_planes.shape(), ray);
        CHECK_EQ(hit.has_value(), expected < kInfinity);
        if (hit && expected < kInfinity) {
            CHECK_NEAR(hit->t, expected, 1e-9 * (1 + expected));
            const Vec3 p = ray.at(hit->t);
            // ∇(xy) = (y, x, 0): across whichever plane was hit, away from the solid xy < 0.
            const Vec3 n = std::fabs(p.x) < std::fabs(p.y) ? Vec3(p.y > 0 ? 1 : -1, 0, 0)
                                                           : Vec3(0, p.x > 0 ? 1 : -1, 0);
            CHECK_NEAR(cross_planes.shape().normal(p, *hit), n, 1e-9);
        }
    }
    // A ray lying in one of the planes: no hit, and no NaN.
    CHECK(!first_hit(cross_planes.shape(), {{-3, 0, 0}, {1, 0, 0}}));
    CHECK(!first_hit(slab.shape(), {{1, -3, 0}, {0, 1, 0}}));
}

TEST(clip_box_with_equal_sides_keeps_a_plane) {
    // x² − 1 = 0 clipped to x = 1 exactly: only that plane shows, whole, without speckles.
    Spec spec = place({1, 0, 0}, {}, -1, {});
    spec.min = {1, -5, -5};
    spec.max = {1, 5, 5};
    const Shape shape = spec.shape();
    Random random(19);
    for (int i = 0; i < 5000; ++i) {
        const Vec3 o{random.uniform(-4, 4), random.uniform(-3, 3), random.uniform(-3, 3)};
        const Vec3 target{1, random.uniform(-4, 4), random.uniform(-4, 4)};
        const Ray ray{o, normalized(target - o)};
        const auto hit = first_hit(shape, ray);
        CHECK(hit.has_value());
        if (hit) CHECK_NEAR(ray.at(hit->t), target, 1e-12 * (1 + length(target - o)));
    }
}

TEST(clip_box_skips_hits_outside_it) {
    // The unit sphere kept only where z <= 0: from above, the near root is clipped and the
    // far one shows; from below the near one shows.
    Spec spec = place({1, 1, 1}, {}, -1, {});
    spec.min = {-2, -2, -2};
    spec.max = {2, 2, 0};
    const Shape shape = spec.shape();
    auto hit = first_hit(shape, {{0, 0, 5}, {0, 0, -1}});
    CHECK(hit.has_value());
    if (hit) CHECK_NEAR(hit->t, 6, 1e-12);
    hit = first_hit(shape, {{0, 0, -5}, {0, 0, 1}});
    CHECK(hit.has_value());
    if (hit) CHECK_NEAR(hit->t, 4, 1e-12);
    // Through the upper half only: nothing.
    CHECK(!first_hit(shape, {{-5, 0, 0.5}, {1, 0, 0}}));
    // The bounds are the lower half of the sphere's box.
    CHECK_NEAR(shape.bounds().min, Vec3(-1, -1, -1), 1e-5);
    CHECK_NEAR(shape.bounds().max, Vec3(1, 1, 0), 1e-5);
    // A clip box that misses the sphere leaves nothing.
    spec.min = {3, 3, 3};
    spec.max = {4, 4, 4};
    CHECK(!first_hit(spec.shape(), {{0, 0, 5}, {0, 0, -1}}));
}

TEST(inside_is_f_negative_and_not_clipped) {
    Spec sphere = place({1, 1, 1}, {}, -4, {1, 1, 1});
    sphere.min = {0, 0, 0};
    sphere.max = {0.5, 0.5, 0.5};
    const Shape s = sphere.shape();
    CHECK(s.has_inside());
    CHECK(s.inside({1, 1, 1}));
    CHECK(s.inside({2.9, 1, 1}));  // outside the clip box, inside the solid
    CHECK(!s.inside({3.1, 1, 1}));
    const Shape paraboloid = place({1, 1, 0}, {0, 0, -0.5}, 0, {}).shape();
    CHECK(paraboloid.inside({0, 0, 1}));
    CHECK(!paraboloid.inside({2, 0, 1}));
    CHECK(!paraboloid.inside({0, 0, -1}));
    const Shape inverted = place({-1, -1, -1}, {}, 1, {}).shape();
    CHECK(!inverted.inside({0, 0, 0}));
    CHECK(inverted.inside({5, 0, 0}));
}

TEST(cross_reports_invisible_crossings) {
    // The unit sphere, kept where z <= 0, crossed from above along the axis.
    Spec spec = place({1, 1, 1}, {}, -1, {});
    spec.min = {-2, -2, -2};
    spec.max = {2, 2, 0};
    const Shape s = spec.shape();
    const Ray down{{0, 0, 5}, {0, 0, -1}};
    Crossing crossing;
    CHECK(s.cross(down, {1e-9, kInfinity}, crossing));
    CHECK_NEAR(crossing.hit.t, 4, 1e-12);
    CHECK(crossing.entering);
    CHECK(!crossing.visible);
    CHECK(s.cross(down, {4 + 1e-9, kInfinity}, crossing));
    CHECK_NEAR(crossing.hit.t, 6, 1e-12);
    CHECK(!crossing.entering);
    CHECK(crossing.visible);
    CHECK(!s.cross(down, {6 + 1e-9, kInfinity}, crossing));
    CHECK(!s.cross(down, {1e-9, 3.9}, crossing));
    // Inside out (f < 0 outside the sphere): the first crossing leaves the solid.
    const Shape inverted = place({-1, -1, -1}, {}, 1, {}).shape();
    CHECK(inverted.cross({{-5, 0, 0}, {1, 0, 0}}, {1e-9, kInfinity}, crossing));
    CHECK_NEAR(crossing.hit.t, 4, 1e-12);
    CHECK(!crossing.entering);
    // The paraboloid along its axis (one root): in from below.
    const Shape paraboloid = place({1, 1, 0}, {0, 0, -0.5}, 0, {}).shape();
    CHECK(paraboloid.cross({{0, 0, -5}, {0, 0, 1}}, {1e-9, kInfinity}, crossing));
    CHECK_NEAR(crossing.hit.t, 5, 1e-12);
    CHECK(crossing.entering);
    CHECK(paraboloid.cross({{0, 0, 5}, {0, 0, -1}}, {1e-9, kInfinity}, crossing));
    CHECK(!crossing.entering);
    // A tangent ray touches the surface (a hit) but does not cross it.
    const Shape unit = place({1, 1, 1}, {}, -1, {}).shape();
    const Ray tangent{{-5, 1, 0}, {1, 0, 0}};
    CHECK(!unit.cross(tangent, {1e-9, kInfinity}, crossing));
    const auto touch = first_hit(unit, tangent);
    CHECK(touch.has_value());
    if (touch) CHECK_NEAR(touch->t, 5, 1e-12);
    // On random rays, entering agrees with f's sign change and crossings alternate.
    Random random(20);
    for (int i = 0; i < 2000; ++i) {
        const Spec h =
            place({1, 1, -1}, {}, i % 2 ? 1.0 : -1.0, random.in_box(2), random_rotation(random));
        const Shape shape = h.shape();
        const Ray ray{random.in_box(5), random.unit_vector()};
        Interval range{1e-9, kInfinity};
        bool inside_now = h.f(ray.origin) < 0;
        for (int n = 0; n < 3 && shape.cross(ray, range, crossing); ++n) {
            CHECK_EQ(crossing.entering, !inside_now);
            const double t = crossing.hit.t;
            CHECK_EQ(h.f(ray.at(t + 1e-6 * (1 + t))) < 0, crossing.entering);
            inside_now = crossing.entering;
            range.t_min = t * (1 + 1e-12) + 1e-12;
        }
    }
}

TEST(a_ray_with_no_direction_gives_no_crossing) {
    // A libFuzzer find: a cylinder hit 1.6e116 along a ray rounded to a point on its axis,
    // where its normal is 0/0, and the mirror ray from there had a NaN direction. The quadric
    // operand of a composite gave that ray a crossing at NaN, and the composite's merge, which
    // moves on by comparing distances, never moved past it: rt hung. Neither cross nor
    // intersect may give a NaN distance, and a composite must end its list.
    Spec spec;
    spec.k = {1, -0.3, 1, 0, 0, 0, -1.05, 0.18, 0.05, 0.957};
    spec.min = {0, 0, -1};
    spec.max = {2.1, 1.1e46, 1};
    const Shape s = spec.shape();
    const Shape composite = parse_shape(
        "20 " +
        object_text(13, {1, -0.3, 1, 0, 0, 0, -1.05, 0.18, 0.05, 0.957, 0, 0, -1, 2.1, 1.1e46, 1}) +
        " 100 1 1 1 0 1 1 0 1  1 1 0 0 0  100 1 1 1 0 1 1 0 1");
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const Ray& ray : {Ray{{0, 0, 0}, {nan, nan, nan}}, Ray{{nan, 0, 0}, {0, 0, 1}}}) {
        Crossing crossing;
        CHECK(!s.cross(ray, {1e-7, kInfinity}, crossing));
        CHECK(!first_hit(s, ray).has_value());
        Crossings list;
        composite.collect(ray, 1e-7, list);
        CHECK(list.empty());
        CHECK(!first_hit(composite, ray).has_value());
    }
}

TEST(bounds_are_tight_for_an_ellipsoid) {
    Random random(21);
    for (int i = 0; i < 500; ++i) {
        const Vec3 axes{random.uniform(0.1, 3), random.uniform(0.1, 3), random.uniform(0.1, 3)};
        const Vec3 c = random.in_box(i % 5 == 0 ? 1e4 : 5);
        const Rotation rot = random_rotation(random);
        const double sign = i % 2 ? 1 : -1;  // −f is the same surface
        Spec spec =
            place(sign * Vec3{1 / (axes.x * axes.x), 1 / (axes.y * axes.y), 1 / (axes.z * axes.z)},
                  {}, -sign, c, rot);
        spec.min = {-1e5, -1e5, -1e5};
        spec.max = {1e5, 1e5, 1e5};
        const Bounds b = spec.shape().bounds();
        // The extent along each world axis: the length of that row of R·diag(axes).
        for (int k = 0; k < 3; ++k) {
            const double half =
                std::hypot(rot.c0[k] * axes.x, rot.c1[k] * axes.y, rot.c2[k] * axes.z);
            const double slack = 1e-6 * half + 1e-9 * std::fabs(c[k]);
            CHECK_NEAR(b.min[k], c[k] - half, slack);
            CHECK_NEAR(b.max[k], c[k] + half, slack);
        }
        for (int n = 0; n < 50; ++n) {
            // Points of the surface as written (its rounded coefficients), from the centre.
            const Ray ray{c, random.unit_vector()};
            const ReferenceRoots roots = reference_roots(spec, ray);
            CHECK_EQ(roots.count, 2);
            if (roots.count == 2) CHECK(b.contains(ray.at(roots.t[1]), 0));
        }
    }
}

// The ellipsoid's extent is worked out in double-double arithmetic on std::fma (not long
// double, whose width differs between x86-64 and arm64), with Q, g and J scaled by a power of
// two first. So an ellipsoid 10^6 from the origin keeps a tight box, and multiplying every
// coefficient by 2^±600 (a product of two would overflow or vanish in a double) does not
// change the box by a bit; beyond a double's range altogether, the clip box bounds it.
TEST(far_and_scaled_ellipsoids_keep_their_box_on_every_machine) {
    Random random(2106);
    for (int i = 0; i < 200; ++i) {
        const Vec3 axes{random.uniform(0.2, 3), random.uniform(0.2, 3), random.uniform(0.2, 3)};
        const Vec3 c = 1e6 * random.unit_vector();
        const Rotation rot = random_rotation(random);
        Spec spec = place({1 / (axes.x * axes.x), 1 / (axes.y * axes.y), 1 / (axes.z * axes.z)}, {},
                          -1, c, rot);
        spec.min = c - Vec3{10, 10, 10};
        spec.max = c + Vec3{10, 10, 10};
        const Shape shape = spec.shape();
        const Bounds b = shape.bounds();
        for (int k = 0; k < 3; ++k) {
            const double half =
                std::hypot(rot.c0[k] * axes.x, rot.c1[k] * axes.y, rot.c2[k] * axes.z);
            // The coefficients as written carry the level f = -1 only to the rounding of J (about
            // 1e12 here), eps |J|, which moves the half-width by half of that, relatively.
            const double slack =
                half * (1e-9 + 4 * std::numeric_limits<double>::epsilon() * std::fabs(spec.k[9]));
            CHECK_NEAR(b.min[k], c[k] - half, slack);
            CHECK_NEAR(b.max[k], c[k] + half, slack);
        }
        const Ray ray{c + 20 * random.unit_vector(), {}};
        const Ray aimed{ray.origin, normalized(c + random.in_box(0.1) - ray.origin)};
        for (const int power : {-600, -300, 300, 600}) {
            Spec scaled = spec;
            for (double& k : scaled.k) k = std::ldexp(k, power);
            const Shape other = scaled.shape();
            const Bounds ob = other.bounds();
            CHECK(ob.min == b.min && ob.max == b.max);
            // Rays see it alike while their own quadratic stays in range (2^±300).
            if (std::abs(power) > 300) continue;
            Hit h1, h2;
            CHECK(shape.intersect(aimed, {1e-9, kInfinity}, h1));
            CHECK(other.intersect(aimed, {1e-9, kInfinity}, h2));
            CHECK_NEAR(h2.t, h1.t, 1e-9 * h1.t);
        }
    }
    // Coefficients whose centre lies beyond a double: bounded by the clip box.
    Spec huge;
    huge.k = {1, 1, 1, 0, 0, 0, -1e300, 0, 0, 1e300};
    huge.min = {-1, -1, -1};
    huge.max = {1, 1, 1};
    const Bounds hb = huge.shape().bounds();
    CHECK(hb.min == huge.min && hb.max == huge.max);
}

TEST(bounds_hold_sampled_points_of_unbounded_forms) {
    // A hyperboloid of one sheet, clipped: every point of it in the clip box is in bounds.
    Spec spec = place({1, 1, -1}, {}, -1, {});
    spec.min = {-3, -3, -2};
    spec.max = {3, 3, 2};
    const Bounds b = spec.shape().bounds();
    CHECK_NEAR(b.min, spec.min, 0.0);
    CHECK_NEAR(b.max, spec.max, 0.0);
    // An empty surface (x² + y² + z² + 1 = 0): no hits, a finite point for bounds.
    const Shape empty = place({1, 1, 1}, {}, 1, {}).shape();
    CHECK(!first_hit(empty, {{0, 0, 5}, {0, 0, -1}}));
    CHECK(std::isfinite(empty.bounds().min.x) && empty.bounds().min == empty.bounds().max);
    CHECK(empty.inside({0, 0, 0}) == false);
}

TEST(rays_leaving_the_surface_do_not_hit_it_again) {
    // Points on a paraboloid and on hyperboloids of one and two sheets, tilted, near the
    // origin and 1e4 away; rays leave them into both sides. The only hit allowed is the other
    // root, −2b/a from the point (the quadratic's roots sum to it), when it is clearly ahead.
    Random random(22);
    int checked = 0, rehit = 0;
    for (int i = 0; i < 30000; ++i) {
        const int form = i % 3;
        const Vec3 c = i % 2 ? random.in_box(1e4) : random.in_box(3);
        const Rotation rot = random_rotation(random);
        const double s = random.uniform(-2, 2), phi = random.uniform(0, 6.283185307179586);
        Spec spec;
        Vec3 local;
        if (form == 0) {
            spec = place({1, 1, 0}, {0, 0, -0.5}, 0, c, rot);
            local = {s * std::cos(phi), s * std::sin(phi), s * s};
        } else if (form == 1) {
            spec = place({1, 1, -1}, {}, -1, c, rot);
            local = {std::cosh(s) * std::cos(phi), std::cosh(s) * std::sin(phi), std::sinh(s)};
        } else {
            spec = place({1, 1, -1}, {}, 1, c, rot);
            local = {std::sinh(s) * std::cos(phi), std::sinh(s) * std::sin(phi),
                     (i % 4 < 2 ? 1 : -1) * std::cosh(s)};
        }
        spec.min = c - Vec3{20, 20, 20};
        spec.max = c + Vec3{20, 20, 20};
        const Shape shape = spec.shape();
        const Vec3 p = c + rot * local;
        const Ray ray{p, random.unit_vector()};
        Hit hit;
        const bool found = shape.intersect(ray, {hit_tolerance(p), kInfinity}, hit);
        // The roots of the surface as written (its rounded coefficients): one is at the point
        // (up to rounding), the other is the one that may be hit.
        const ReferenceRoots roots = reference_roots(spec, ray);
        if (roots.count != 2) continue;
        const double other =
            std::fabs(roots.t[0]) > std::fabs(roots.t[1]) ? roots.t[0] : roots.t[1];
        const Vec3 q = spec.gradient(p);
        if (std::fabs(other) < 1e-3 || std::fabs(dot(normalized(q), ray.direction)) < 1e-3)
            continue;  // grazing: either answer is right
        ++checked;
        const bool expected = other > 0 && spec.in_box(ray.at(other), 0);
        if (found && hit.t < 1e-3) ++rehit;
        CHECK_EQ(found, expected);
        // The point itself is rounded to its coordinates' size, which moves a root along a
        // slanting ray by that over the cosine of the slant.
        const double slant = std::fabs(dot(normalized(q), ray.direction));
        if (found && expected)
            CHECK_NEAR(hit.t, other,
                       1e-9 * (1 + other) + 1e-13 * (1 + max_abs_component(p)) / slant);
    }
    CHECK(checked > 25000);
    CHECK_EQ(rehit, 0);
}

TEST(far_origin_is_accurate) {
    // The unit sphere seen from a million units away.
    const Shape s = place({1, 1, 1}, {}, -1, {}).shape();
    Random random(23);
    for (int i = 0; i < 1000; ++i) {
        const Vec3 o = 1e6 * random.unit_vector();
        const Ray ray{o, normalized(random.in_box(0.6) - o)};
        const auto expected = sphere_distance({}, 1, ray);
        const auto hit = first_hit(s, ray);
        CHECK_EQ(hit.has_value(), expected.has_value());
        if (hit && expected) CHECK_NEAR(hit->t, *expected, 1e-9);
    }
}

TEST(best_distance_so_far_stops_early) {
    const Shape s = place({1, 1, 1}, {}, -1, {0, 0, -10}).shape();
    Hit hit{123, 7};
    CHECK(!s.intersect({{0, 0, 0}, {0, 0, -1}}, {1e-9, 8.5}, hit));
    CHECK_EQ(hit.t, 123.0);  // left alone on a miss
    CHECK(s.intersect({{0, 0, 0}, {0, 0, -1}}, {1e-9, 9.5}, hit));
    CHECK_NEAR(hit.t, 9, 1e-12);
}

TEST(read_errors_name_the_field) {
    const std::string viewer = kTestViewer;
    const std::string surface = " 100 1 1 1 0 1 1 0 1";
    CHECK_CONTAINS(scene_error(viewer + "13 0 0 0 0 0 0 0 0 0 5  -1 -1 -1  1 1 1" + surface),
                   "test.in:2:4: quadric coefficients A to I must not all be zero (the equation "
                   "would be the constant J = 0)");
    CHECK_CONTAINS(scene_error(viewer + "13 1 1 1 0 0 0 0 0 0 -1  -1 -1 -1  1 -2 1" + surface),
                   "test.in:2:36: quadric clip box max must be >= its min in every component, "
                   "got y max -2 < min -1");
    CHECK_CONTAINS(scene_error(viewer + "13 1 1 x 0 0 0 0 0 0 -1  -1 -1 -1  1 1 1" + surface),
                   "test.in:2:8: expected quadric coefficient C (a number), got 'x'");
    CHECK_CONTAINS(scene_error(viewer + "13 1 1 1 0 0 0 0 0 0 -1  -1 -1 -1  1 1"),
                   "test.in:2:39: unexpected end of file: expected quadric clip box max");
    CHECK_CONTAINS(scene_error(viewer + "13 1 1 1 0 0 0 0 0 0 -1  -1 -1 inf  1 1 1" + surface),
                   "test.in:2:32: quadric clip box min must be a finite number, got 'inf'");
    // Equal sides are allowed, and a plane written as a quadric (first order only) too.
    CHECK_EQ(scene_error(viewer + "13 1 0 0 0 0 0 0 0 0 -1  1 -1 -1  1 1 1" + surface), "");
    CHECK_EQ(scene_error(viewer + "13 0 0 0 0 0 0 0 1 0 -1  -1 -1 -1  1 1 1" + surface), "");
}
