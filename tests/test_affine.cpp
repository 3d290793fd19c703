// Affine (ID 7) against closed forms: an affine of a sphere is an ellipsoid, solved here as the
// quadric (x - C)^T Q (x - C) = r^2 with Q = M^T M and M inverted by Gauss-Jordan elimination,
// a different route from the code's cross products and ray transform.
#include <cmath>
#include <string>

#include "random_rays.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

// A 3x3 matrix by rows, only for the test's own arithmetic.
struct Mat3 {
    double m[3][3] = {};

    static Mat3 from_columns(const Vec3& x, const Vec3& y, const Vec3& z) {
        Mat3 a;
        for (int i = 0; i < 3; ++i) {
            a.m[i][0] = x[i];
            a.m[i][1] = y[i];
            a.m[i][2] = z[i];
        }
        return a;
    }
    Vec3 column(int j) const { return {m[0][j], m[1][j], m[2][j]}; }
    Vec3 operator*(const Vec3& v) const {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
                m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
    Mat3 operator*(const Mat3& b) const {
        Mat3 c;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                for (int k = 0; k < 3; ++k) c.m[i][j] += m[i][k] * b.m[k][j];
        return c;
    }
    Mat3 transposed() const {
        Mat3 t;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) t.m[i][j] = m[j][i];
        return t;
    }
    double determinant() const {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
               m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    }
    // Gauss-Jordan elimination with partial pivoting.
    Mat3 inverse() const {
        double a[3][6] = {};
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) a[i][j] = m[i][j];
            a[i][3 + i] = 1;
        }
        for (int col = 0; col < 3; ++col) {
            int pivot = col;
            for (int r = col + 1; r < 3; ++r)
                if (std::fabs(a[r][col]) > std::fabs(a[pivot][col])) pivot = r;
            for (int j = 0; j < 6; ++j) std::swap(a[col][j], a[pivot][j]);
            const double p = a[col][col];
            for (int j = 0; j < 6; ++j) a[col][j] /= p;
            for (int r = 0; r < 3; ++r) {
                if (r == col) continue;
                const double f = a[r][col];
                for (int j = 0; j < 6; ++j) a[r][j] -= f * a[col][j];
            }
        }
        Mat3 inv;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) inv.m[i][j] = a[i][3 + j];
        return inv;
    }
};

Mat3 random_frame(Random& random) {
    for (;;) {
        const Mat3 f = Mat3::from_columns(random.in_box(2), random.in_box(2), random.in_box(2));
        // Well-conditioned enough that 1e-8 relative accuracy is a fair demand.
        if (std::fabs(f.determinant()) > 0.5) return f;
    }
}

// A rotation about a unit axis by an angle (Rodrigues' formula).
Mat3 rotation(const Vec3& k, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    Mat3 r;
    const double kv[3] = {k.x, k.y, k.z};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r.m[i][j] = (1 - c) * kv[i] * kv[j] + (i == j ? c : 0);
    r.m[0][1] -= s * k.z;
    r.m[0][2] += s * k.y;
    r.m[1][0] += s * k.z;
    r.m[1][2] -= s * k.x;
    r.m[2][0] -= s * k.y;
    r.m[2][1] += s * k.x;
    return r;
}

// "7 O X Y Z " for a frame given as origin and matrix.
std::string affine_prefix(const Vec3& o, const Mat3& f) {
    const Vec3 x = f.column(0), y = f.column(1), z = f.column(2);
    return object_text(7, {o.x, o.y, o.z, x.x, x.y, x.z, y.x, y.y, y.z, z.x, z.y, z.z}) + " ";
}

std::string sphere_text(double r, const Vec3& c) { return object_text(1, {r, c.x, c.y, c.z}); }

// The smallest root beyond 1e-9 of a t^2 + b t + c = 0, solved without cancellation.
std::optional<double> smallest_positive_root(double a, double b, double c) {
    const double disc = b * b - 4 * a * c;
    if (disc < 0) return std::nullopt;
    const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    double t0 = q / a, t1 = q != 0 ? c / q : t0;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > 1e-9) return t0;
    if (t1 > 1e-9) return t1;
    return std::nullopt;
}

// The ellipsoid (x - centre)^T q (x - centre) = r^2.
struct Ellipsoid {
    Vec3 centre;
    Mat3 q;
    double r;

    double value(const Vec3& x) const {
        const Vec3 d = x - centre;
        return dot(d, q * d);
    }
    std::optional<double> distance(const Ray& ray) const {
        const Vec3 oc = ray.origin - centre;
        const Vec3 qd = q * ray.direction;
        return smallest_positive_root(dot(ray.direction, qd), 2 * dot(oc, qd),
                                      dot(oc, q * oc) - r * r);
    }
    Vec3 normal(const Vec3& x) const { return normalized(q * (x - centre)); }
};

std::string nested_affines(int depth) {
    std::string text = kTestViewer;
    const std::string identity = "7 0 0 0 1 0 0 0 1 0 0 0 1\n";
    for (int i = 0; i < depth; ++i) text += identity;
    text += "1 1 0 0 0\n100 1 1 1 0 1 1 0 1\n";
    return text;
}

}  // namespace

TEST(affine_sphere_is_the_ellipsoid_quadric) {
    Random random(7);
    RayCounts counts;
    int from_inside = 0, mirrored = 0;
    for (int i = 0; i < 6000; ++i) {
        const Mat3 f = random_frame(random);
        const Vec3 o = random.in_box(3);
        const double r = random.uniform(0.2, 1.5);
        const Vec3 c = random.in_box(1);
        const Shape s = parse_shape(affine_prefix(o, f) + sphere_text(r, c));
        const Mat3 m = f.inverse();
        const Ellipsoid e{o + f * c, m.transposed() * m, r};
        if (f.determinant() < 0) ++mirrored;

        // A third of the rays start inside; of the rest, most aim at the ellipsoid.
        const bool start_inside = i % 3 == 0;
        const Vec3 origin =
            start_inside ? e.centre + f * (random.in_box(r * 0.55)) : e.centre + random.in_box(8);
        const Vec3 aim = e.centre + f * random.in_box(r * 1.3);
        const Ray ray{origin, i % 4 ? normalized(aim - origin) : random.unit_vector()};
        const auto found = compare_first_hit(s, ray, {e.distance(ray)}, 1e-8, counts);
        if (!found) continue;
        if (start_inside) ++from_inside;
        const Vec3 p = found->point;
        CHECK_NEAR(e.value(p), r * r, 1e-8 * (1 + r * r));
        CHECK_NEAR(s.normal(p, found->hit), e.normal(p), 1e-7);
        CHECK(s.bounds().contains(p, 1e-9));
        CHECK(s.has_inside());
        // Points just inside and outside along the normal.
        const Vec3 n = e.normal(p);
        CHECK(s.inside(p - 1e-4 * n));
        CHECK(!s.inside(p + 1e-4 * n));
    }
    CHECK(counts.hits > 2000);
    CHECK(counts.misses > 1000);
    CHECK(from_inside > 1000);
    CHECK(mirrored > 1000);  // frames with det F < 0 keep outward normals
}

TEST(original_example_is_the_textbook_ellipsoid) {
    // Section 2.7: X (1,0,0), Y (0,2,0), Z (0,0,2), sphere 0.5 at (0,0.5,0):
    // the ellipsoid x^2 / 0.25 + (y - 1)^2 + z^2 = 1.
    const Shape s = parse_shape("7 0 0 0  1 0 0  0 2 0  0 0 2  1 0.5 0 0.5 0");
    struct Case {
        Ray ray;
        double t;
        Vec3 normal;
    };
    const double diagonal = std::sqrt(2.0 / 5.0);
    const Case cases[] = {
        {{{0, 1, 5}, {0, 0, -1}}, 4, {0, 0, 1}},
        {{{5, 1, 0}, {-1, 0, 0}}, 4.5, {1, 0, 0}},
        {{{0, -5, 0}, {0, 1, 0}}, 5, {0, -1, 0}},
        {{{0, 7, 0}, {0, -1, 0}}, 5, {0, 1, 0}},
        // From the centre, inside, toward (1, 0, 1): t^2/2 (4 + 1) = 1.
        {{{0, 1, 0}, normalized(Vec3(1, 0, 1))}, diagonal, normalized(Vec3(4, 0, 1))},
    };
    for (const Case& c : cases) {
        const auto hit = first_hit(s, c.ray);
        CHECK(hit.has_value());
        if (!hit) continue;
        CHECK_NEAR(hit->t, c.t, 1e-12);
        CHECK_NEAR(s.normal(c.ray.at(hit->t), *hit), c.normal, 1e-12);
    }
    CHECK(!first_hit(s, {{0.51, 1, 5}, {0, 0, -1}}));
    CHECK(first_hit(s, {{0.49, 1, 5}, {0, 0, -1}}).has_value());
    const Bounds b = s.bounds();
    CHECK_NEAR(b.min, Vec3(-0.5, 0, -1), 1e-15);
    CHECK_NEAR(b.max, Vec3(0.5, 2, 1), 1e-15);
}

TEST(rotated_flat_primitives_match_the_rotated_primitive_written_directly) {
    Random random(11);
    int plane_hits = 0, disk_hits = 0, sphere_hits = 0;
    for (int i = 0; i < 3000; ++i) {
        const Mat3 rot = rotation(random.unit_vector(), random.uniform(0, 6.3));
        const Vec3 o = random.in_box(3);
        const Vec3 n = random.unit_vector();
        const Vec3 c = random.in_box(2);
        const double radius = random.uniform(0.3, 2);
        const double d = random.uniform(-2, 2);
        const Vec3 wn = rot * n, wc = o + rot * c;

        const Shape local_plane =
            parse_shape(affine_prefix(o, rot) + object_text(2, {d, n.x, n.y, n.z}));
        const Shape world_plane = parse_shape(object_text(2, {d + dot(wn, o), wn.x, wn.y, wn.z}));
        const Shape local_disk = parse_shape(
            affine_prefix(o, rot) + object_text(3, {c.x, c.y, c.z, n.x, n.y, n.z, radius}));
        const Shape world_disk =
            parse_shape(object_text(3, {wc.x, wc.y, wc.z, wn.x, wn.y, wn.z, radius}));
        const Shape local_sphere = parse_shape(affine_prefix(o, rot) + sphere_text(radius, c));
        const Shape world_sphere = parse_shape(sphere_text(radius, wc));

        const Vec3 origin = wc + random.in_box(6);
        const Ray ray{origin, normalized(wc + random.in_box(radius * 1.5) - origin)};
        auto compare = [&](const Shape& local, const Shape& world, int& count, bool flat) {
            const auto a = first_hit(local, ray), b = first_hit(world, ray);
            if (flat && b && std::fabs(length(ray.at(b->t) - wc) - radius) < 1e-7) return;
            CHECK_EQ(a.has_value(), b.has_value());
            if (!a || !b) return;
            ++count;
            CHECK_NEAR(a->t, b->t, 1e-9 * (1 + b->t));
            const Vec3 p = ray.at(a->t);
            CHECK_NEAR(local.normal(p, *a), world.normal(p, *b), 1e-9);
        };
        compare(local_plane, world_plane, plane_hits, false);
        compare(local_disk, world_disk, disk_hits, true);
        compare(local_sphere, world_sphere, sphere_hits, false);
        CHECK_EQ(local_plane.has_inside(), true);
        CHECK_EQ(local_disk.has_inside(), false);
    }
    CHECK(plane_hits > 2000);
    CHECK(disk_hits > 500);
    CHECK(sphere_hits > 1000);
}

TEST(translation_only_frame_moves_the_sphere) {
    Random random(3);
    Mat3 identity;
    for (int i = 0; i < 3; ++i) identity.m[i][i] = 1;
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
        const Vec3 o = random.in_box(4), c = random.in_box(2);
        const double r = random.uniform(0.2, 2);
        const Shape moved = parse_shape(affine_prefix(o, identity) + sphere_text(r, c));
        const Shape direct = parse_shape(sphere_text(r, o + c));
        const Vec3 origin = random.in_box(8);
        const Ray ray{origin, normalized(o + c + random.in_box(r * 1.5) - origin)};
        const auto a = first_hit(moved, ray), b = first_hit(direct, ray);
        CHECK_EQ(a.has_value(), b.has_value());
        if (!a || !b) continue;
        ++hits;
        CHECK_NEAR(a->t, b->t, 1e-12 * (1 + b->t));
        CHECK_NEAR(moved.normal(ray.at(a->t), *a), direct.normal(ray.at(b->t), *b), 1e-12);
        CHECK_NEAR(moved.bounds().min, direct.bounds().min, 1e-12);
        CHECK_NEAR(moved.bounds().max, direct.bounds().max, 1e-12);
    }
    CHECK(hits > 500);
}

TEST(nested_affines_compose) {
    Random random(5);
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
        const Mat3 f1 = random_frame(random), f2 = random_frame(random);
        const Vec3 o1 = random.in_box(2), o2 = random.in_box(1), c = random.in_box(1);
        const double r = random.uniform(0.3, 1);
        // Local to world: O1 + F1 (O2 + F2 p) = (O1 + F1 O2) + (F1 F2) p.
        const Shape nested =
            parse_shape(affine_prefix(o1, f1) + affine_prefix(o2, f2) + sphere_text(r, c));
        const Shape composed =
            parse_shape(affine_prefix(o1 + f1 * o2, f1 * f2) + sphere_text(r, c));
        const Vec3 centre = o1 + f1 * (o2 + f2 * c);
        const Vec3 origin = centre + random.in_box(10);
        const Ray ray{origin, normalized(centre + (f1 * f2) * random.in_box(r) - origin)};
        const auto a = first_hit(nested, ray), b = first_hit(composed, ray);
        CHECK_EQ(a.has_value(), b.has_value());
        if (!a || !b) continue;
        ++hits;
        CHECK_NEAR(a->t, b->t, 1e-8 * (1 + b->t));
        const Vec3 p = ray.at(a->t);
        CHECK_NEAR(nested.normal(p, *a), composed.normal(p, *b), 1e-7);
        CHECK(nested.bounds().contains(p, 1e-9));
        CHECK(nested.has_inside());
    }
    CHECK(hits > 1000);
}

TEST(best_distance_so_far_stops_early) {
    // The ellipsoid of the original's example, hit at t = 4 from (0, 1, 5).
    const Shape s = parse_shape("7 0 0 0  1 0 0  0 2 0  0 0 2  1 0.5 0 0.5 0");
    const Ray ray{{0, 1, 5}, {0, 0, -1}};
    Hit hit{123, 7};
    CHECK(!s.intersect(ray, {1e-9, 3.9}, hit));
    CHECK_EQ(hit.t, 123.0);  // left alone on a miss
    CHECK(s.intersect(ray, {1e-9, 4.1}, hit));
    CHECK_NEAR(hit.t, 4, 1e-12);
    // t_min is scaled too: starting beyond the near side finds the far side at t = 6.
    CHECK(s.intersect(ray, {4.5, kInfinity}, hit));
    CHECK_NEAR(hit.t, 6, 1e-12);
    // A shrinking frame: local distances are twice the world's, and so must the range be.
    const Shape shrunk = parse_shape("7 0 0 0  0.5 0 0  0 0.5 0  0 0 0.5  1 2 0 0 0");
    CHECK(shrunk.intersect({{0, 0, 5}, {0, 0, -1}}, {1e-9, 4.1}, hit));
    CHECK_NEAR(hit.t, 4, 1e-12);
    CHECK(shrunk.intersect({{0, 0, 5}, {0, 0, -1}}, {4.5, 6.1}, hit));
    CHECK_NEAR(hit.t, 6, 1e-12);
    CHECK(!shrunk.intersect({{0, 0, 5}, {0, 0, -1}}, {4.5, 5.9}, hit));
}

TEST(inside_follows_the_inner_primitive) {
    const Shape ellipsoid = parse_shape("7 0 0 0  1 0 0  0 2 0  0 0 2  1 0.5 0 0.5 0");
    CHECK(ellipsoid.inside({0, 1, 0}));
    CHECK(ellipsoid.inside({0, 1.95, 0}));
    CHECK(ellipsoid.inside({0, 1, 0.95}));
    CHECK(!ellipsoid.inside({0.55, 1, 0}));
    CHECK(!ellipsoid.inside({0, 2.05, 0}));
    // A half-space y < 1 carried by a frame that swaps y and z becomes z < 1.
    const Shape half = parse_shape("7 0 0 0  1 0 0  0 0 1  0 1 0  2 1 0 1 0");
    CHECK(half.has_inside());
    CHECK(half.inside({0, 5, 0.5}));
    CHECK(!half.inside({0, 0.5, 5}));
    CHECK(!std::isnan(half.bounds().min.x));
    CHECK(half.bounds().min.x == -kInfinity && half.bounds().max.z == kInfinity);
    // Flat primitives enclose nothing, however they are placed.
    const Shape disk = parse_shape("7 0 0 0  2 0 0  0 2 0  0 0 2  3 0 0 0 0 0 1 1");
    CHECK(!disk.has_inside());
    CHECK(!disk.inside({0, 0, 0}));
    const Shape nested_disk =
        parse_shape("7 0 0 0  2 0 0  0 2 0  0 0 2  7 1 1 1  1 0 0  0 1 0  0 0 1  3 0 0 0 0 0 1 1");
    CHECK(!nested_disk.has_inside());
}

TEST(affine_reads_its_surface_after_the_inner_primitive) {
    const Scene scene = parse_scene(std::string(kTestViewer) +
                                    "7 0 0 0 1 0 0 0 2 0 0 0 2  1 0.5 0 0.5 0\n"
                                    "100 0.25 0.5 0.75 0 1 1 0 1\n"
                                    "1 1 5 5 5  100 1 1 1 0 1 1 0 1\n");
    CHECK_EQ(scene.objects.size(), std::size_t{2});
    CHECK_NEAR(scene.objects[0].surface->at({0, 0, 0}).colour, Spectrum(0.25, 0.5, 0.75), 0);
}

TEST(singular_frame_is_an_error_at_the_axes) {
    const std::string v = kTestViewer;
    const std::string sphere = " 1 1 0 0 0 100 1 1 1 0 1 1 0 1";
    CHECK_CONTAINS(scene_error(v + "7 0 0 0  1 0 0  2 0 0  0 0 1" + sphere),
                   "test.in:2:10: affine frame is singular");
    CHECK_CONTAINS(scene_error(v + "7 0 0 0 0 0 0 0 1 0 0 0 1" + sphere),
                   "test.in:2:9: affine frame is singular");
    // Z within rounding of the plane of X and Y.
    CHECK_CONTAINS(scene_error(v + "7 0 0 0 1 0 0 0 1 0 1 1 1e-14" + sphere),
                   "affine frame is singular");
    CHECK_CONTAINS(scene_error(v + "7 0 0 0 1e200 0 0 0 1e200 0 0 0 1e200" + sphere),
                   "test.in:2:9: affine frame is too large");
    CHECK_CONTAINS(scene_error(v + "7 0 0 0 1e-120 0 0 0 1e-120 0 0 0 1e-120" + sphere),
                   "affine frame is");
    // The test is relative: a uniformly tiny frame or a skewed but independent one is fine.
    CHECK_EQ(scene_error(v + "7 0 0 0 1e-8 0 0 0 1e-8 0 0 0 1e-8" + sphere), std::string());
    CHECK_EQ(scene_error(v + "7 0 0 0 1 0 0 1 1e-6 0 0 0 1" + sphere), std::string());
}

TEST(inner_object_must_be_a_primitive) {
    const std::string v = kTestViewer;
    CHECK_CONTAINS(scene_error(v + "7 0 0 0 1 0 0 0 1 0 0 0 1 100 1 1 1 0 1 1 0 1"),
                   "test.in:2:27: expected affine inner primitive ID (a primitive, 1-99), got 100");
    CHECK_CONTAINS(scene_error(v + "7 0 0 0 1 0 0 0 1 0 0 0 1 1 -1 0 0 0 100 1 1 1 0 1 1 0 1"),
                   "test.in:2:29: sphere radius must be > 0, got -1");
    CHECK_CONTAINS(scene_error(v + "7 0 0 0 1 0 0 0 1 0 0 0"),
                   "unexpected end of file: expected affine axis Z");
}

TEST(nesting_is_limited) {
    // kMaxNesting affines in a chain read; with one more, the sphere inside them all (on line
    // kMaxNesting + 3, after the viewer and the affines) is one level too deep.
    CHECK_EQ(scene_error(nested_affines(kMaxNesting)), std::string());
    const std::string too_deep = scene_error(nested_affines(kMaxNesting + 1));
    CHECK_CONTAINS(too_deep, join("test.in:", kMaxNesting + 3, ":1: objects nested more than ",
                                  kMaxNesting, " deep"));
    CHECK_CONTAINS(scene_error(nested_affines(40)), "nested more than");
    // Deep input is refused at the limit, long before the stack is in danger.
    CHECK_CONTAINS(scene_error(nested_affines(10000)), "nested more than");
}
