// The mesh (14): distances and normals against the closed form of an octahedron, exact
// agreement with the same triangles written one by one (a brute-force search over thousands
// of them), no gaps at shared edges and vertices, zero-area triangles, the interval, an affine
// of a mesh, and its errors with their places.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "cli_util.h"
#include "rt/render.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

constexpr double kTMin = 1e-9;
const char* const kSurface = "  100  1 1 1  0 1  1  0 1\n";

struct IndexTriple {
    int a, b, c;
};

struct MeshData {
    std::vector<Vec3> vertices;
    std::vector<IndexTriple> triangles;

    std::string text() const {
        std::string s = join("14 ", vertices.size(), ' ', triangles.size(), '\n');
        for (const Vec3& v : vertices) s += join(v.x, ' ', v.y, ' ', v.z, '\n');
        for (const IndexTriple& t : triangles) s += join(t.a, ' ', t.b, ' ', t.c, '\n');
        return s;
    }
    Shape shape() const { return parse_shape(text()); }
    // Each triangle as a triangle primitive (5), in file order.
    std::vector<Shape> separate_triangles() const {
        std::vector<Shape> shapes;
        for (const IndexTriple& t : triangles) {
            const Vec3 &a = vertices[static_cast<std::size_t>(t.a)],
                       &b = vertices[static_cast<std::size_t>(t.b)],
                       &c = vertices[static_cast<std::size_t>(t.c)];
            shapes.push_back(
                parse_shape(object_text(5, {a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z})));
        }
        return shapes;
    }
};

// The octahedron |x - c|_1 = r: vertices c +- r e_k, one face per octant, wound so that
// (v1 - v0) x (v2 - v0) points out of the octant's face.
MeshData octahedron(const Vec3& c, double r) {
    MeshData m;
    for (int k = 0; k < 3; ++k)
        for (const double sign : {1.0, -1.0}) {
            Vec3 e;
            e = k == 0 ? Vec3(sign, 0, 0) : k == 1 ? Vec3(0, sign, 0) : Vec3(0, 0, sign);
            m.vertices.push_back(c + e * r);
        }
    for (int sx = 0; sx < 2; ++sx)
        for (int sy = 0; sy < 2; ++sy)
            for (int sz = 0; sz < 2; ++sz) {
                // Vertex 2k is +e_k, 2k + 1 is -e_k; an odd number of minus signs mirrors the
                // octant, so two vertices swap to keep the winding outward.
                const int x = sx, y = 2 + sy, z = 4 + sz;
                if ((sx + sy + sz) % 2 == 0)
                    m.triangles.push_back({x, y, z});
                else
                    m.triangles.push_back({x, z, y});
            }
    return m;
}

// Where a ray first meets the solid octahedron's surface by the slab method over its eight
// face planes s.(x - c) = r, s in {-1, 1}^3: the outward unit normal there, and how clearly
// that plane wins (the gap to the runner-up), so that rays near edges can be left out.
struct ConvexHit {
    double t;
    Vec3 normal;
    double margin;  // how far the ray is from grazing or from choosing another plane
};
std::optional<ConvexHit> octahedron_hit(const Vec3& c, double r, const Ray& ray) {
    double enter = -kInfinity, exit = kInfinity, enter_second = -kInfinity, exit_second = kInfinity;
    Vec3 enter_normal, exit_normal;
    const Vec3 u = ray.origin - c;
    for (const double sx : {1.0, -1.0})
        for (const double sy : {1.0, -1.0})
            for (const double sz : {1.0, -1.0}) {
                const Vec3 s(sx, sy, sz);
                const double a = dot(s, ray.direction), b = r - dot(s, u);
                if (a == 0) {
                    if (b < 0) return std::nullopt;
                    continue;
                }
                const double t = b / a;
                if (a < 0) {
                    if (t > enter) {
                        enter_second = enter;
                        enter = t;
                        enter_normal = s / std::sqrt(3.0);
                    } else {
                        enter_second = std::max(enter_second, t);
                    }
                } else if (t < exit) {
                    exit_second = exit;
                    exit = t;
                    exit_normal = s / std::sqrt(3.0);
                } else {
                    exit_second = std::min(exit_second, t);
                }
            }
    if (enter > exit) return ConvexHit{kInfinity, {}, enter - exit};
    if (enter > kTMin)
        return ConvexHit{enter, enter_normal, std::min(exit - enter, enter - enter_second)};
    if (exit > kTMin)
        return ConvexHit{exit, exit_normal, std::min(exit - enter, exit_second - exit)};
    return std::nullopt;
}

// A height field z = f(x, y) over [-2, 2]^2 as an n x n grid of quads, two triangles each:
// every inner vertex is shared by six triangles.
MeshData height_field(int n, Random& random) {
    MeshData m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const double x = -2 + 4.0 * i / n, y = -2 + 4.0 * j / n;
            m.vertices.emplace_back(
                x, y, 0.3 * std::sin(2 * x) * std::cos(1.5 * y) + random.uniform(-0.02, 0.02));
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
            m.triangles.push_back({a, b, c});
            m.triangles.push_back({a, c, d});
        }
    return m;
}

// A closed double cone: a ring of n vertices round the z axis with an apex above and below,
// so each apex is shared by n triangles.
MeshData bipyramid(int n, Random& random) {
    MeshData m;
    m.vertices.emplace_back(0, 0, 1.5);
    m.vertices.emplace_back(0, 0, -1.2);
    for (int i = 0; i < n; ++i) {
        const double angle = 2 * std::numbers::pi * i / n, radius = random.uniform(0.9, 1.1);
        m.vertices.emplace_back(radius * std::cos(angle), radius * std::sin(angle),
                                random.uniform(-0.1, 0.1));
    }
    for (int i = 0; i < n; ++i) {
        const int a = 2 + i, b = 2 + (i + 1) % n;
        m.triangles.push_back({0, a, b});
        m.triangles.push_back({1, b, a});
    }
    return m;
}

Ray ray_from_to(const Vec3& origin, const Vec3& aim) { return {origin, normalized(aim - origin)}; }

}  // namespace

TEST(octahedron_distances_and_normals_match_the_closed_form) {
    Random random(14);
    const Vec3 c(0.3, -0.2, 0.5);
    const double r = 1.3;
    const Shape mesh = octahedron(c, r).shape();
    int hits = 0, misses = 0, from_inside = 0;
    for (int i = 0; i < 20000; ++i) {
        // A quarter of the rays start inside the solid.
        const Vec3 origin = c + (i % 4 == 1 ? random.in_box(r / 3) : random.in_box(4));
        Ray ray = ray_from_to(origin, c + random.in_box(0.8 * r));
        if (i % 5 == 0) ray.direction = random.unit_vector();
        const auto expected = octahedron_hit(c, r, ray);
        const auto hit = first_hit(mesh, ray);
        if (expected && expected->margin < 1e-9) continue;  // grazing or at an edge
        if (!expected || expected->t == kInfinity) {
            CHECK(!hit);
            ++misses;
            continue;
        }
        CHECK(hit.has_value());
        if (!hit) continue;
        ++hits;
        if (std::fabs(origin.x - c.x) + std::fabs(origin.y - c.y) + std::fabs(origin.z - c.z) < r)
            ++from_inside;
        const double cos = std::fabs(dot(ray.direction, expected->normal));
        CHECK_NEAR(hit->t, expected->t, 1e-13 * (1 + 10 + hit->t) / cos);
        CHECK_NEAR(mesh.normal(ray.at(hit->t), *hit), expected->normal, 1e-14);
    }
    CHECK(hits > 10000);
    CHECK(misses > 4000);
    CHECK(from_inside > 4000);
    const Bounds box = mesh.bounds();
    CHECK_NEAR(box.min, c - Vec3(r, r, r), 0);
    CHECK_NEAR(box.max, c + Vec3(r, r, r), 0);
    CHECK(!mesh.has_inside());
}

TEST(thousands_of_triangles_agree_exactly_with_a_search_over_each) {
    // A height field, a soup of random triangles through it, and some triangles written twice,
    // the second time wound the other way: hit at the same distance, the first written wins,
    // which its normal shows.
    Random random(1414);
    MeshData m = height_field(40, random);
    for (int i = 0; i < 400; ++i) {
        const int base = static_cast<int>(m.vertices.size());
        const Vec3 centre = random.in_box(2);
        for (int k = 0; k < 3; ++k) m.vertices.push_back(centre + random.in_box(0.4));
        m.triangles.push_back({base, base + 1, base + 2});
    }
    const std::size_t written_once = m.triangles.size();
    for (std::size_t i = 0; i < written_once; i += 23) {
        const IndexTriple t = m.triangles[i];
        m.triangles.push_back({t.a, t.c, t.b});
    }
    CHECK(m.triangles.size() > 3500);
    const Shape mesh = m.shape();
    const std::vector<Shape> each = m.separate_triangles();

    int hits = 0, ties = 0;
    for (int i = 0; i < 3000; ++i) {
        Ray ray = ray_from_to(random.in_box(4), Vec3(random.uniform(-2, 2), random.uniform(-2, 2),
                                                     random.uniform(-0.5, 0.5)));
        if (i % 5 == 0) ray.direction = random.unit_vector();
        double best = kInfinity;
        std::size_t best_index = 0;
        int at_best = 0;
        Hit best_hit;
        for (std::size_t k = 0; k < each.size(); ++k) {
            Hit h;
            if (!each[k].intersect(ray, {kTMin, kInfinity}, h)) continue;
            if (h.t < best) {
                best = h.t;
                best_index = k;
                best_hit = h;
                at_best = 1;
            } else if (h.t == best) {
                ++at_best;
            }
        }
        Hit hit;
        const bool found = mesh.intersect(ray, {kTMin, kInfinity}, hit);
        CHECK_EQ(found, best < kInfinity);
        if (!found || best == kInfinity) continue;
        ++hits;
        if (at_best > 1) ++ties;
        CHECK_EQ(hit.t, best);
        const Vec3 p = ray.at(hit.t);
        CHECK_NEAR(mesh.normal(p, hit), each[best_index].normal(p, best_hit), 0);
    }
    CHECK(hits > 2000);
    CHECK(ties > 20);
}

TEST(rays_from_far_away_agree_with_a_search_over_each) {
    // Rays from 1e3 to 4e26 away (reflected off a huge sphere or torus, say) aimed at a mesh
    // near the origin. From beyond about 1e7 the boxes' margins, relative to the distance,
    // cover the whole mesh, and from 1e17 on the origin's rounding does too, so every
    // triangle is tested: slower, but the answer must still be the search's, bit for bit.
    Random random(2718);
    const MeshData m = height_field(12, random);
    const Shape mesh = m.shape();
    const std::vector<Shape> each = m.separate_triangles();
    int hits = 0;
    for (const double far : {1e3, 1e7, 1e12, 1e17, 1e20, 4.4e26}) {
        for (int i = 0; i < 200; ++i) {
            const Vec3 origin = random.unit_vector() * far;
            const Vec3 aim(random.uniform(-2, 2), random.uniform(-2, 2), random.uniform(-1, 1));
            const Ray ray = ray_from_to(origin, aim);
            Hit best;
            for (const Shape& triangle : each) {
                Hit h;
                if (triangle.intersect(ray, {kTMin, best.t}, h)) best = h;
            }
            Hit hit;
            const bool found = mesh.intersect(ray, {kTMin, kInfinity}, hit);
            CHECK_EQ(found, best.t < kInfinity);
            CHECK_EQ(mesh.intersect_any(ray, {kTMin, kInfinity}), found);
            if (!found) continue;
            ++hits;
            CHECK_EQ(std::bit_cast<std::uint64_t>(hit.t), std::bit_cast<std::uint64_t>(best.t));
        }
    }
    // About 390: from 1e17 on, no test can resolve the mesh, and these rays miss in both.
    CHECK(hits > 350);
}

TEST(rays_at_shared_edges_and_vertices_never_slip_through) {
    Random random(4141);
    int rays = 0;
    // Every ray runs from outside toward a point of the surface, crossing it there, so it
    // must hit no farther than that point (rounding moves the aim by far less than 1e-9).
    auto check_reaches = [&](const Shape& mesh, const Ray& ray, double distance) {
        const auto hit = first_hit(mesh, ray);
        CHECK(hit.has_value());
        if (hit) CHECK(hit->t <= distance + 1e-9);
        ++rays;
    };

    const MeshData cone = bipyramid(24, random);
    const Shape closed = cone.shape();
    // From outside the convex solid, along the line from a point well inside it through the
    // aim: such a ray enters the solid at the aim, however sharp the corner there.
    auto from_outside = [&](const Vec3& aim) {
        const Vec3 inside = Vec3(0, 0, 0.1) + random.in_box(0.3);
        const Vec3 origin = aim + normalized(aim - inside) * random.uniform(2, 6);
        check_reaches(closed, ray_from_to(origin, aim), length(aim - origin));
    };
    for (const Vec3& v : cone.vertices)
        for (int k = 0; k < 20; ++k) from_outside(v);
    for (const IndexTriple& t : cone.triangles)
        for (const auto& [p, q] : {std::pair{t.a, t.b}, std::pair{t.b, t.c}, std::pair{t.c, t.a}})
            for (int k = 0; k < 20; ++k) {
                const Vec3 a = cone.vertices[static_cast<std::size_t>(p)];
                const Vec3 b = cone.vertices[static_cast<std::size_t>(q)];
                from_outside(a + (b - a) * random.uniform(0, 1));
            }

    // From above and below a height field, steeply enough to cross it inside the grid.
    const int n = 12;
    const MeshData field = height_field(n, random);
    const Shape sheet = field.shape();
    auto through_sheet = [&](const Vec3& aim) {
        const double side = random.uniform() < 0.5 ? 1 : -1;
        const Vec3 dir =
            normalized(Vec3(random.uniform(-0.3, 0.3), random.uniform(-0.3, 0.3), side));
        const Vec3 origin = aim + dir * random.uniform(1, 4);
        check_reaches(sheet, ray_from_to(origin, aim), length(aim - origin));
    };
    for (int j = 1; j < n; ++j)
        for (int i = 1; i < n; ++i) {
            const int v = j * (n + 1) + i;
            const Vec3 here = field.vertices[static_cast<std::size_t>(v)];
            for (int k = 0; k < 10; ++k) {
                through_sheet(here);
                // Along the edges to the right, up and diagonally up-right.
                for (const int w : {v + 1, v + n + 1, v + n + 2})
                    through_sheet(here + (field.vertices[static_cast<std::size_t>(w)] - here) *
                                             random.uniform(0, 1));
            }
        }
    CHECK(rays > 8000);
}

TEST(the_interval_is_open_at_both_ends) {
    Random random(7);
    const Shape mesh = bipyramid(16, random).shape();
    for (int i = 0; i < 2000; ++i) {
        const Ray ray = ray_from_to(random.in_box(4), random.in_box(0.8));
        const auto hit = first_hit(mesh, ray);
        if (!hit) continue;
        Hit other{-1, -1};
        // Up to, but not including, the hit: nothing.
        CHECK(!mesh.intersect(ray, {kTMin, hit->t}, other));
        CHECK_EQ(other.t, -1.0);  // left alone
        // Just past it: exactly the same hit.
        CHECK(mesh.intersect(ray, {kTMin, std::nextafter(hit->t, kInfinity)}, other));
        CHECK_EQ(other.t, hit->t);
        CHECK_EQ(other.part, hit->part);
        // From the hit on: only farther ones (the far side of the solid).
        Hit beyond;
        if (mesh.intersect(ray, {hit->t, kInfinity}, beyond)) CHECK(beyond.t > hit->t);
    }
}

TEST(zero_area_triangles_are_skipped_and_counted) {
    // A unit square as two triangles, and three with no area: a repeated index, two vertices
    // at the same place, and three vertices on a line.
    const std::string mesh =
        "14 6 5\n"
        "0 0 0  1 0 0  1 1 0  0 1 0  2 2 0  1 0 0\n"
        "0 1 2  0 2 3  0 0 1  1 5 2  0 2 4\n";
    const Scene scene = parse_scene(join(kTestViewer, mesh, kSurface));
    CHECK_EQ(scene.skipped_triangles, 3u);
    CHECK_EQ(scene.mesh_triangles, 2u);  // the two kept
    const Shape& shape = scene.objects.at(0).shape;
    CHECK(first_hit(shape, {{0.5, 0.25, 3}, {0, 0, -1}}).has_value());
    CHECK(first_hit(shape, {{0.25, 0.5, 3}, {0, 0, -1}}).has_value());
    CHECK(!first_hit(shape, {{1.5, 1.5, 3}, {0, 0, -1}}).has_value());
    // The box holds the triangles kept, not the point (2, 2, 0) that only a skipped one uses.
    CHECK_NEAR(shape.bounds().max, Vec3(1, 1, 0), 0);
    CHECK_EQ(parse_scene(join(kTestViewer, octahedron({}, 1).text(), kSurface)).skipped_triangles,
             0u);

    // rt -r reports them; with none, the summary is as for any scene.
    const auto dir = work_dir("mesh_summary");
    write_file(dir / "skips.in", join(kTestViewer, mesh, kSurface));
    RunResult r = run_rt(dir, "-r skips.in");
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.out,
             std::string("skips.in: 1 objects, 0 lights, 4x4, 3 zero-area triangles skipped\n"));
    write_file(dir / "one.in",
               join(kTestViewer, "14 3 2  0 0 0  1 0 0  0 1 0  0 1 2  1 1 2", kSurface));
    CHECK_EQ(run_rt(dir, "-r one.in").out,
             std::string("one.in: 1 objects, 0 lights, 4x4, 1 zero-area triangle skipped\n"));
    write_file(dir / "none.in", join(kTestViewer, octahedron({}, 1).text(), kSurface));
    CHECK_EQ(run_rt(dir, "-r none.in").out, std::string("none.in: 1 objects, 0 lights, 4x4\n"));
}

TEST(an_affine_of_a_mesh_is_the_mesh_with_its_vertices_moved) {
    Random random(77);
    const MeshData local = bipyramid(12, random);
    const Vec3 o(1, 2, -1), x(2, 0, 0.5), y(0, 1.5, 0), z(0.3, -0.2, 0.8);
    MeshData world = local;
    for (Vec3& v : world.vertices) v = o + v.x * x + v.y * y + v.z * z;
    const std::string frame =
        object_text(7, {o.x, o.y, o.z, x.x, x.y, x.z, y.x, y.y, y.z, z.x, z.y, z.z});
    const Shape moved = parse_shape(frame + ' ' + local.text());
    const Shape direct = world.shape();
    int hits = 0;
    for (int i = 0; i < 3000; ++i) {
        const Ray ray = ray_from_to(o + random.in_box(6), o + random.in_box(1.5));
        const auto a = first_hit(moved, ray), b = first_hit(direct, ray);
        CHECK_EQ(a.has_value(), b.has_value());
        if (!a || !b) continue;
        ++hits;
        CHECK_NEAR(a->t, b->t, 1e-12 * (1 + b->t));
        const Vec3 p = ray.at(b->t);
        CHECK_NEAR(moved.normal(p, *a), direct.normal(p, *b), 1e-12);
    }
    CHECK(hits > 1000);
    CHECK(!moved.has_inside());

    // And as a whole scene: it reads and renders, the same on any number of threads.
    const Scene scene = parse_scene(
        join("102  1 2 8  1 2 -1  0.5 0 0  0 0.5 0  24 24\n103 0.2 0.2 0.2\n101 3 5 8 40 40 40\n",
             frame, ' ', local.text(), kSurface));
    RenderOptions one, two;
    one.threads = 1;
    two.threads = 2;
    const Raster a = render(scene, one), b = render(scene, two);
    bool same = true, lit = false;
    for (int py = 0; py < a.height(); ++py)
        for (int px = 0; px < a.width(); ++px) {
            same = same && a.at(px, py) == b.at(px, py);
            lit = lit || a.at(px, py)[0] > 0.3;
        }
    CHECK(same);
    CHECK(lit);
}

TEST(counts_and_limits) {
    // A mesh that claims two billion vertices but ends at once fails at the end of the file:
    // it allocates only for what is there.
    CHECK_CONTAINS(scene_error(join(kTestViewer, "14 2000000000 2000000000  0 0 0")),
                   "test.in:2:32: unexpected end of file: expected mesh vertex 1");
    // The largest coordinates allowed work.
    CHECK_EQ(
        scene_error(join(kTestViewer, "14 3 1  1e100 0 0  0 1e100 0  0 0 -1e100  0 1 2", kSurface)),
        std::string());
}

TEST(the_documented_tetrahedron_faces_outward) {
    // The example in docs/format.md: every face's normal points away from the centroid.
    const Shape tetrahedron =
        parse_shape("14 4 4  0 0 0  1 0 0  0 1 0  0 0 1  0 2 1  0 3 2  0 1 3  1 2 3");
    const Vec3 centroid(0.25, 0.25, 0.25);
    Random random(4);
    int hits = 0;
    for (int i = 0; i < 500; ++i) {
        const Ray ray = ray_from_to(centroid + random.unit_vector() * 3, centroid);
        const auto hit = first_hit(tetrahedron, ray);
        CHECK(hit.has_value());
        if (!hit) continue;
        ++hits;
        const Vec3 p = ray.at(hit->t);
        CHECK(dot(tetrahedron.normal(p, *hit), p - centroid) > 0);
    }
    CHECK_EQ(hits, 500);
}

TEST(a_large_mesh_is_the_same_built_on_several_threads) {
    // Large enough (over 100,000 triangles) that its hierarchy is built on two threads.
    Random random(2);
    const std::string text = join(kTestViewer, height_field(240, random).text(), kSurface);
    std::istringstream one_in(text), two_in(text);
    const Scene one = read_scene(one_in, "test.in", {}, 1);
    const Scene two = read_scene(two_in, "test.in", {}, 2);
    const Shape &a = one.objects.at(0).shape, &b = two.objects.at(0).shape;
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
        const Ray ray =
            ray_from_to(random.in_box(4), Vec3(random.uniform(-2, 2), random.uniform(-2, 2), 0));
        const auto ha = first_hit(a, ray), hb = first_hit(b, ray);
        CHECK_EQ(ha.has_value(), hb.has_value());
        if (!ha || !hb) continue;
        ++hits;
        CHECK_EQ(ha->t, hb->t);
        CHECK_EQ(ha->part, hb->part);
    }
    CHECK(hits > 1500);
}
