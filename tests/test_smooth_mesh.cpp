// The smooth mesh (16): the mesh's geometry with blended vertex normals for shading. A
// tessellated sphere with exact normals shades as the analytic sphere (1) does, within a
// stated tolerance and with no black speckles; flat vertex normals degrade to the mesh (14)
// bit for bit; the blend at a hit is the closed form; errors name their places.
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "check.h"
#include "primitives/watertight.h"
#include "rt/render.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

const char* const kLight = "103 0 0 0\n104 4 5 6  1 1 1\n";
const char* const kSurface = "100  0.9 0.7 0.5  0.3 20 0.8 0 1\n";

std::string viewer(int size) {
    return join("102  0 0 4  0 0 0  0.4 0 0  0 0.4 0  ", size, ' ', size, '\n');
}

// A UV sphere of unit radius at the origin: `stacks` bands from pole to pole, `slices` around,
// each vertex's normal its position (exact unit normals). With `smooth` false, ID 14.
std::string uv_sphere(int stacks, int slices, bool smooth) {
    const double pi = std::acos(-1.0);
    std::vector<Vec3> v;
    v.push_back({0, 1, 0});
    for (int i = 1; i < stacks; ++i)
        for (int j = 0; j < slices; ++j) {
            const double theta = pi * i / stacks, phi = 2 * pi * j / slices;
            v.push_back({std::sin(theta) * std::cos(phi), std::cos(theta),
                         -std::sin(theta) * std::sin(phi)});
        }
    v.push_back({0, -1, 0});
    const int last = static_cast<int>(v.size()) - 1;
    auto ring = [&](int i, int j) { return 1 + (i - 1) * slices + (j % slices); };
    std::vector<std::array<int, 3>> t;
    for (int j = 0; j < slices; ++j) {
        t.push_back({0, ring(1, j), ring(1, j + 1)});
        for (int i = 1; i + 1 < stacks; ++i) {
            t.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
            t.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
        }
        t.push_back({last, ring(stacks - 1, j + 1), ring(stacks - 1, j)});
    }
    std::ostringstream out;
    out.precision(17);
    out << (smooth ? 16 : 14) << ' ' << v.size() << ' ' << t.size() << '\n';
    for (const Vec3& p : v) {
        out << p.x << ' ' << p.y << ' ' << p.z;
        if (smooth) out << "  " << p.x << ' ' << p.y << ' ' << p.z;
        out << '\n';
    }
    for (const auto& k : t) out << k[0] << ' ' << k[1] << ' ' << k[2] << '\n';
    return out.str();
}

Raster render_text(const std::string& text, bool accelerate = true) {
    RenderOptions options;
    options.threads = 1;
    options.accelerate = accelerate;
    return render(parse_scene(text), options);
}

// Where pixel (x, y) of viewer(size) looks, as a share of the unit sphere's silhouette radius
// (1 on the silhouette): the sphere at distance 4 subtends tan(asin(1/4)) on the image plane
// at distance 1, whose half-width is 0.4.
double silhouette_share(int x, int y, int size) {
    const double a = 0.4 * (2.0 * x - size) / size, b = 0.4 * (2.0 * y - size) / size;
    return std::hypot(a, b) / std::tan(std::asin(0.25));
}

std::string show_numbers(const Vec3& v) { return join(v.x, ' ', v.y, ' ', v.z); }

double difference(const Spectrum& a, const Spectrum& b) {
    double d = 0;
    for (std::size_t i = 0; i < kSpectrumComponents; ++i) d = std::max(d, std::fabs(a[i] - b[i]));
    return d;
}

}  // namespace

TEST(a_tessellated_sphere_shades_as_the_analytic_sphere) {
    const int size = 64;
    const Raster exact = render_text(join(viewer(size), kLight, "1 1 0 0 0\n", kSurface));
    const Raster smooth =
        render_text(join(viewer(size), kLight, uv_sphere(32, 64, true), kSurface));
    const Raster flat = render_text(join(viewer(size), kLight, uv_sphere(32, 64, false), kSurface));
    // Away from the silhouette (where the polygon lies inside the circle) the smooth mesh is
    // within 0.03 of the sphere everywhere, and differs by more than 0.01 on under 4 % of
    // pixels; the flat mesh, with the same triangles, shows its facets far more.
    int smooth_over = 0, flat_over = 0, inside = 0;
    double smooth_max = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            if (silhouette_share(x, y, size) > 0.9) continue;
            ++inside;
            const double ds = difference(smooth.at(x, y), exact.at(x, y));
            smooth_max = std::max(smooth_max, ds);
            if (ds > 0.01) ++smooth_over;
            if (difference(flat.at(x, y), exact.at(x, y)) > 0.01) ++flat_over;
        }
    CHECK(inside > 1000);
    CHECK(smooth_max < 0.03);
    CHECK(smooth_over < inside / 25);
    CHECK(flat_over > 4 * smooth_over);
}

TEST(a_coarse_smooth_sphere_has_no_black_speckles) {
    // 8 x 16 triangles: the shading normal and the face disagree a lot near the silhouette
    // and the terminator. Wherever the analytic sphere is clearly lit, so is the mesh.
    const int size = 96;
    const Raster exact = render_text(join(viewer(size), kLight, "1 1 0 0 0\n", kSurface));
    const Raster coarse = render_text(join(viewer(size), kLight, uv_sphere(8, 16, true), kSurface));
    int lit = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            if (!(exact.at(x, y)[0] > 0.1)) continue;
            ++lit;
            // Near the edge the polygon, inside the circle, is missed.
            if (silhouette_share(x, y, size) > 0.85) continue;
            CHECK(coarse.at(x, y)[0] > 0);
        }
    CHECK(lit > 1000);
}

TEST(flat_vertex_normals_render_the_mesh_bit_for_bit) {
    // Every triangle with vertices of its own, each normal its face normal: ID 16 is ID 14.
    const double pi = std::acos(-1.0);
    std::ostringstream flat, smooth;
    flat.precision(17);
    smooth.precision(17);
    std::vector<std::array<Vec3, 3>> triangles;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 12; ++j) {
            auto at = [&](int a, int b) {
                const double theta = pi * (a + 1) / 8, phi = 2 * pi * b / 12;
                return Vec3{std::sin(theta) * std::cos(phi), std::cos(theta),
                            -std::sin(theta) * std::sin(phi)};
            };
            triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    const std::size_t n = triangles.size();
    flat << "14 " << 3 * n << ' ' << n << '\n';
    smooth << "16 " << 3 * n << ' ' << n << '\n';
    for (const auto& t : triangles) {
        const Vec3 f = face_normal(t[0], t[1], t[2]);
        for (const Vec3& p : t) {
            flat << p.x << ' ' << p.y << ' ' << p.z << '\n';
            smooth << p.x << ' ' << p.y << ' ' << p.z << "  " << f.x << ' ' << f.y << ' ' << f.z
                   << '\n';
        }
    }
    for (std::size_t i = 0; i < n; ++i) {
        flat << 3 * i << ' ' << 3 * i + 1 << ' ' << 3 * i + 2 << '\n';
        smooth << 3 * i << ' ' << 3 * i + 1 << ' ' << 3 * i + 2 << '\n';
    }
    // A mirror and glass too, so that the reflected and refracted directions are compared.
    const std::string rest = join(kLight, "2 0  0 1 0  100 0.3 0.6 0.3 0 1 0.9 0 1\n");
    for (const char* surface :
         {kSurface, "100 0.9 0.9 0.9 0.5 30 0.4 0 1\n", "114 1 1 1 0.1 50 0 1.5 0 0 0\n"}) {
        const Raster a = render_text(join(viewer(40), rest, flat.str(), surface));
        const Raster b = render_text(join(viewer(40), rest, smooth.str(), surface));
        bool same = true;
        for (int y = 0; y < 40; ++y)
            for (int x = 0; x < 40; ++x) same = same && a.at(x, y) == b.at(x, y);
        CHECK(same);
    }
}

TEST(the_shading_normal_is_the_blend_of_the_vertex_normals) {
    // One triangle in z = 0 with vertex normals n0, n1, n2 (not unit); the ray down the z axis
    // through (x, y) hits where the weights are (1 - x - y, x, y).
    const Vec3 n0{0, 0, 2}, n1{1, 0, 1}, n2{0, -3, 3};
    const Shape mesh = parse_shape(join("16 3 1  0 0 0 ", show_numbers(n0), "  1 0 0 ",
                                        show_numbers(n1), "  0 1 0 ", show_numbers(n2), "  0 1 2"));
    for (const auto& [x, y] : {std::pair{0.2, 0.3}, {0.6, 0.1}, {0.05, 0.9}, {1.0 / 3, 1.0 / 3}}) {
        Hit hit;
        const Ray ray{{x, y, 5}, {0, 0, -1}};
        CHECK(mesh.intersect(ray, {1e-9, kInfinity}, hit));
        CHECK_NEAR(hit.t, 5.0, 1e-12);
        const Vec3 expected = normalized((1 - x - y) * n0 + x * n1 + y * n2);
        CHECK_NEAR(mesh.shading_normal(ray.at(hit.t), hit), expected, 1e-12);
        CHECK_NEAR(mesh.normal(ray.at(hit.t), hit), Vec3(0, 0, 1), 1e-15);
    }
    // Through an affine the blend is carried back as a normal is.
    const Shape moved =
        parse_shape(join("7  0 0 0  2 0 0  0 1 0  0 0 1  16 3 1  0 0 0 ", show_numbers(n0),
                         "  1 0 0 ", show_numbers(n1), "  0 1 0 ", show_numbers(n2), "  0 1 2"));
    Hit hit;
    const Ray ray{{0.4, 0.3, 5}, {0, 0, -1}};
    CHECK(moved.intersect(ray, {1e-9, kInfinity}, hit));
    const Vec3 local = (1 - 0.2 - 0.3) * n0 + 0.2 * n1 + 0.3 * n2;
    CHECK_NEAR(moved.shading_normal(ray.at(hit.t), hit),
               normalized(Vec3(local.x / 2, local.y, local.z)), 1e-12);
}

TEST(smooth_mesh_errors_name_their_places) {
    const std::string v = "0 0 0  0 0 1   1 0 0  0 0 1   0 1 0  0 0 1\n";
    CHECK_CONTAINS(scene_error(join(kTestViewer, "16 3 1\n0 0 0  0 0 1   1 0 0  0 0 0\n")),
                   "test.in:3:23: smooth mesh vertex 1 normal must have a non-zero, finite length");
    CHECK_CONTAINS(scene_error(join(kTestViewer, "16 3 1\n", v, "0 1 3\n", kSurface)),
                   "test.in:4:5: smooth mesh triangle 0 vertex index must be in [0, 3), got 3");
    CHECK_CONTAINS(scene_error(join(kTestViewer, "16 2 1\n")),
                   "test.in:2:4: smooth mesh vertex count must be between 3 and 2147483647, got 2");
    CHECK_CONTAINS(scene_error(join(kTestViewer, "16 3 1\n", v, "0 1 1\n", kSurface)),
                   "test.in:2:6: smooth mesh has no triangle with non-zero area (all 1 are "
                   "degenerate)");
    CHECK_CONTAINS(
        scene_error(join(kTestViewer, "16 3 1\n", v, "0 1 1.5\n", kSurface)),
        "test.in:4:5: smooth mesh triangle 0 vertex index must be a whole number, got 1.5");
    CHECK_CONTAINS(scene_error(join(kTestViewer, "16 3 1\n1e101 0 0  0 0 1\n")),
                   "test.in:3:1: smooth mesh vertex 0 coordinates must be at most 1e+100");
    CHECK_CONTAINS(scene_error(join(kTestViewer, "16 3 1\n", v, "0 1\n")),
                   "expected smooth mesh triangle 0 vertex index");
}

TEST(the_hierarchy_agrees_with_the_linear_scan) {
    const std::string text =
        join(viewer(48), kLight, uv_sphere(10, 20, true), "100 0.9 0.9 0.9 0.5 30 0.4 0 1\n",
             "2 0  0 1 0  100 0.3 0.6 0.3 0 1 0.9 0 1\n");
    const Raster a = render_text(text, true), b = render_text(text, false);
    bool same = true;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 48; ++x) same = same && a.at(x, y) == b.at(x, y);
    CHECK(same);
}
