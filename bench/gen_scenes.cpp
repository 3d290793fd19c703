// Writes the benchmark scenes, each twice: as an rt scene (NAME.in) and as the equivalent
// POV-Ray 3.7 scene (NAME.pov), so that both renderers can be timed on the same picture.
//   rt_bench_scenes [--size N] DIR [SCENE ...]
// SCENE is spheres-COUNT, mesh-COUNT (triangles), mirror-COUNT (spheres, a square grid),
// shells-COUNT, rings-COUNT (chain-mail rings of cylinders), gears-COUNT (concave polygons),
// lattice-SIDE (cylinders and spheres), sphereflake-LEVELS, tetra-LEVELS or mountain-LEVELS;
// COUNT may end in k or m. The default is spheres-10k spheres-100k spheres-1m mesh-500k
// mirror-49. --size sets the image's width and height (default 1024). The output depends only
// on the arguments: every random number comes from a fixed seed.
//
// How the two files are made to render the same picture (bench/README.md says more):
// - Camera: rt traces pixel (X, Y) through the pixel's corner, p0 + a x + b y with
//   a = (2X - xres) / xres and b = -(2Y - yres) / yres; POV-Ray's perspective camera traces
//   the pixel's centre, direction + u right + v up with u = (X + 1/2) / xres - 1/2 and
//   v = 1/2 - (Y + 1/2) / yres. With right = 2x, up = 2y and direction = (p0 - e) - x / xres
//   + y / yres the two rays coincide.
// - Shading: rt's simple surface (colour c, ks, ke, kd) lights a point with
//   I_a kd c + sum over lights of I (kd c (n.s) + ks max(0, r.s)^ke) + ks (reflected ray).
//   POV-Ray's finish { ambient kd diffuse kd phong ks phong_size ke reflection ks } with
//   global ambient_light I_a computes the same terms; assumed_gamma 1 keeps its colours
//   linear like rt's, and the background is I_a because rt's escaping rays bring back I_a.
// - Depth: rt's -d D traces D generations of secondary rays after the primary ray;
//   POV-Ray counts the primary ray as level 1, so max_trace_level is D + 1. adc_bailout
//   matches rt's default weight cut-off (-w 0.01).
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

struct Vec {
    double x = 0, y = 0, z = 0;
};
Vec operator+(Vec a, Vec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec operator-(Vec a, Vec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec operator*(double s, Vec a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(Vec a, Vec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec cross(Vec a, Vec b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Vec normalized(Vec a) { return (1 / std::sqrt(dot(a, a))) * a; }

// Uniform numbers from a fixed seed. The engine's output is fixed by the C++ standard, the
// standard distributions' is not, so the mapping to [lo, hi) is done here.
class Random {
  public:
    explicit Random(std::uint64_t seed) : engine_(seed) {}
    double uniform(double lo, double hi) {
        return lo + (hi - lo) * static_cast<double>(engine_() >> 11) * 0x1p-53;
    }

  private:
    std::mt19937_64 engine_;
};

// rt's simple surface (ID 100) without transmission: kt = 0, ior = 1.
struct Finish {
    Vec colour;
    double ks = 0, ke = 1, kd = 1;
};

struct Sphere {
    Vec centre;
    double radius = 1;
};

// An open cylinder from `base` to base + axis (rt's ID 9 from 0 to 1 along the axis).
struct Cylinder {
    Vec base, axis;
    double radius = 1;
};

// A flat polygon, concave allowed (ID 11): its vertices in order round the outline, given in
// the plane's own coordinates, vertex k at origin + points[k][0] u + points[k][1] v. rt reads
// the vertices; POV-Ray, whose polygon is lost where its points are not coplanar to its own
// tolerance (seven digits are not), reads the 2D points and the plane as a matrix.
struct Polygon {
    Vec origin, u, v;
    std::vector<std::array<double, 2>> points;
    Vec vertex(std::size_t k) const { return origin + points[k][0] * u + points[k][1] * v; }
};

// Objects that share one finish: rt reads them after one default surface (105, then 106
// for each), POV-Ray after one #declare, which keeps both files small.
struct Group {
    Finish finish;
    std::vector<Sphere> spheres;
    std::vector<Cylinder> cylinders = {};
    std::vector<Polygon> polygons = {};
};

struct Plane {
    Vec normal;  // unit length, so that rt and POV-Ray read the same offset
    double offset = 0;
    Finish finish;
};

struct Mesh {
    std::vector<Vec> vertices;
    std::vector<std::array<std::size_t, 3>> triangles;
    Finish finish;
};

struct Camera {
    Vec eye, look_at, x, y;
    int xres = 0, yres = 0;
};

struct Light {
    Vec position, intensity;
};

struct Scene {
    std::string name;
    int depth = 0;  // rt's -d
    Camera camera;
    Vec ambient;
    std::vector<Light> lights;
    std::vector<Plane> planes;
    std::vector<Group> groups;
    std::vector<Mesh> meshes;
};

// A camera at `eye` looking at `look_at`, with y up and the given horizontal field of view;
// the pixels are square.
Camera camera(Vec eye, Vec look_at, double fov_degrees, int size) {
    const Vec forward = normalized(look_at - eye);
    const Vec right = normalized(cross(forward, {0, 1, 0}));
    const Vec up = cross(right, forward);
    const double half_width = std::tan(fov_degrees * std::numbers::pi / 360);
    return {eye, look_at, half_width * right, half_width * up, size, size};
}

// A scene with a floor (the plane y = 0), light from the upper left and, dimmer, from the
// right, and a bluish sky; the scene is meant to be rendered to `depth`.
Scene lit_scene(int depth, const Camera& view, const Finish& floor_finish) {
    Scene scene;
    scene.depth = depth;
    scene.camera = view;
    scene.ambient = {0.15, 0.18, 0.24};
    scene.lights = {{{-30, 40, -25}, {0.8, 0.8, 0.75}}, {{35, 30, -10}, {0.45, 0.45, 0.5}}};
    scene.planes.push_back({{0, 1, 0}, 0, floor_finish});
    return scene;
}

Finish random_finish(Random& random) {
    return {{random.uniform(0.2, 1), random.uniform(0.2, 1), random.uniform(0.2, 1)},
            random.uniform(0.15, 0.45),
            random.uniform(10, 80),
            random.uniform(0.5, 0.8)};
}

// `count` spheres over a 20 x 20 square of floor. The radius shrinks as 1/sqrt(count) and the
// layer they float in with it, so every count covers the same share of the floor: a larger
// count is the same picture with finer grain, seen by the same camera.
Scene spheres(long count, int size) {
    Scene scene =
        lit_scene(3, camera({0, 18, -15}, {0, 0, 1}, 45, size), {{0.6, 0.6, 0.6}, 0.1, 10, 0.8});
    Random random(1);
    const double radius = 0.085 * std::sqrt(1e4 / static_cast<double>(count));
    constexpr long kFinishes = 16;
    for (long g = 0; g < kFinishes; ++g) {
        Group group{random_finish(random), {}};
        for (long i = g; i < count; i += kFinishes) {
            const double r = radius * random.uniform(0.6, 1.4);
            group.spheres.push_back({{random.uniform(-10, 10), r + random.uniform(0, 2 * radius),
                                      random.uniform(-10, 10)},
                                     r});
        }
        scene.groups.push_back(std::move(group));
    }
    return scene;
}

// A (2, 3) torus knot: the curve winds twice round the vertical axis and three times round
// the tube of a torus with radii 2 and 0.8. Returns the point at t in [0, 2 pi) and the
// torus's normal there, which is perpendicular to the curve because the curve lies on it.
std::array<Vec, 2> knot(double t) {
    constexpr double kMajor = 2, kMinor = 0.8;
    const double phi = 2 * t, theta = 3 * t;
    const Vec normal{std::cos(theta) * std::cos(phi), std::sin(theta),
                     std::cos(theta) * std::sin(phi)};
    const Vec on_core{kMajor * std::cos(phi), 1.5, kMajor * std::sin(phi)};
    return {on_core + kMinor * normal, normal};
}

// A ribbed tube round a torus knot, about `count` triangles, hovering over a floor.
Scene mesh(long count, int size) {
    Scene scene = lit_scene(3, camera({0, 6.5, -7.5}, {0, 1.2, 0}, 60, size),
                            {{0.5, 0.55, 0.6}, 0.15, 10, 0.8});
    // A ring of `around` vertices every step along the knot; two triangles per quad.
    const std::size_t around =
        std::max<std::size_t>(3, std::lround(std::sqrt(static_cast<double>(count) / 50)));
    const std::size_t along = std::max<std::size_t>(3, count / (2 * around));
    Mesh m;
    m.finish = {{0.85, 0.6, 0.25}, 0.3, 40, 0.7};
    for (std::size_t i = 0; i < along; ++i) {
        const double t = 2 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(along);
        const auto [centre, normal] = knot(t);
        const Vec tangent = normalized(knot(t + 1e-6)[0] - knot(t - 1e-6)[0]);
        const Vec binormal = cross(tangent, normal);
        const double radius = 0.32 * (1 + 0.15 * std::sin(60 * t));  // 60 ribs
        for (std::size_t j = 0; j < around; ++j) {
            const double u =
                2 * std::numbers::pi * static_cast<double>(j) / static_cast<double>(around);
            m.vertices.push_back(centre + radius * (std::cos(u) * normal + std::sin(u) * binormal));
        }
    }
    for (std::size_t i = 0; i < along; ++i) {
        const std::size_t next = (i + 1) % along;
        for (std::size_t j = 0; j < around; ++j) {
            const std::size_t k = (j + 1) % around;
            const std::size_t a = i * around + j, b = next * around + j;
            const std::size_t c = next * around + k, d = i * around + k;
            m.triangles.push_back({a, b, c});
            m.triangles.push_back({a, c, d});
        }
    }
    scene.meshes.push_back(std::move(m));
    return scene;
}

// A square grid of mirror spheres on a mirror floor: many bounces per pixel.
Scene mirror(long count, int size) {
    const long side = std::max(1L, std::lround(std::sqrt(static_cast<double>(count))));
    const double spacing = 2.2, extent = spacing * static_cast<double>(side - 1) / 2;
    Scene scene = lit_scene(7, camera({0, extent + 3, -1.4 * extent - 5}, {0, 0, 0.5}, 50, size),
                            {{0.5, 0.5, 0.55}, 0.5, 60, 0.5});
    Random random(2);
    for (long i = 0; i < side; ++i) {
        for (long j = 0; j < side; ++j) {
            const Finish tint{
                {random.uniform(0.6, 1), random.uniform(0.6, 1), random.uniform(0.6, 1)},
                0.8,
                200,
                0.15};
            const Vec centre{static_cast<double>(i) * spacing - extent, 0.9,
                             static_cast<double>(j) * spacing - extent};
            scene.groups.push_back({tint, {{centre, 0.9}}});
        }
    }
    return scene;
}

// A sphereflake in the SPD's spirit: a sphere with nine spheres a third its size round it (six
// round its equator, three above), each of them with nine more, `levels` deep (COUNT is the
// level count: 9^0 + ... + 9^levels spheres). Mirror-like, over a floor.
void flake(Group& group, Vec centre, double radius, Vec up, int level) {
    group.spheres.push_back({centre, radius});
    if (level == 0) return;
    // A frame round `up`: child directions are fixed angles in it.
    const Vec side =
        normalized(std::fabs(up.x) < 0.9 ? cross(up, {1, 0, 0}) : cross(up, {0, 1, 0}));
    const Vec other = cross(up, side);
    const double child = radius / 3;
    for (int i = 0; i < 9; ++i) {
        const bool ring = i < 6;
        const double around = 2 * std::numbers::pi * (ring ? i / 6.0 : (i - 6) / 3.0 + 1 / 12.0);
        const double elevation = ring ? 0 : std::numbers::pi / 3.5;
        const Vec direction =
            std::cos(elevation) * (std::cos(around) * side + std::sin(around) * other) +
            std::sin(elevation) * up;
        flake(group, centre + (radius + child) * direction, child, direction, level - 1);
    }
}

Scene sphereflake(long levels, int size) {
    Scene scene = lit_scene(4, camera({2.1, 2.6, -3.9}, {0, 0.55, 0}, 45, size),
                            {{0.55, 0.5, 0.45}, 0.15, 10, 0.8});
    Group group{{{0.75, 0.7, 0.65}, 0.5, 60, 0.5}, {}};
    flake(group, {0, 0.6, 0}, 0.5, {0, 1, 0}, static_cast<int>(std::min(levels, 7L)));
    scene.groups.push_back(std::move(group));
    return scene;
}

// Nested shells of spheres, the SPD's "shells" idea: COUNT spheres on a spiral, each smaller
// than the one before and overlapping it heavily, so that most rays meet many spheres'
// boxes. The spiral's size is fixed: more spheres overlap more.
Scene shells(long count, int size) {
    Scene scene =
        lit_scene(3, camera({0, 3.2, -5.5}, {0, 1, 0}, 45, size), {{0.5, 0.55, 0.6}, 0.1, 10, 0.8});
    Random random(4);
    constexpr long kFinishes = 8;
    for (long g = 0; g < kFinishes; ++g) scene.groups.push_back({random_finish(random), {}});
    for (long i = 0; i < count; ++i) {
        const double f = static_cast<double>(i) / static_cast<double>(count);
        const double angle = 6 * 2 * std::numbers::pi * f;  // six turns
        const double radius = 0.9 * (1 - 0.93 * f);
        const double reach = 1.6 * (1 - f);
        scene.groups[static_cast<std::size_t>(i % kFinishes)].spheres.push_back(
            {{reach * std::cos(angle), 1 + 0.4 * std::sin(3 * angle) * (1 - f),
              reach * std::sin(angle)},
             radius});
    }
    return scene;
}

// A recursive tetrahedron (Sierpinski's), `levels` deep (COUNT is the level count), as one
// mesh: 4^levels small tetrahedra of four triangles each.
void tetrahedra(Mesh& m, const std::array<Vec, 4>& corners, int level) {
    if (level == 0) {
        const std::size_t base = m.vertices.size();
        for (const Vec& c : corners) m.vertices.push_back(c);
        m.triangles.push_back({base, base + 1, base + 2});
        m.triangles.push_back({base, base + 3, base + 1});
        m.triangles.push_back({base + 1, base + 3, base + 2});
        m.triangles.push_back({base, base + 2, base + 3});
        return;
    }
    for (int k = 0; k < 4; ++k) {
        std::array<Vec, 4> half;
        for (int j = 0; j < 4; ++j)
            half[static_cast<std::size_t>(j)] =
                0.5 * (corners[static_cast<std::size_t>(k)] + corners[static_cast<std::size_t>(j)]);
        tetrahedra(m, half, level - 1);
    }
}

Scene tetra(long levels, int size) {
    Scene scene = lit_scene(3, camera({1.6, 2.4, -3.4}, {0, 0.75, 0}, 45, size),
                            {{0.5, 0.55, 0.6}, 0.15, 10, 0.8});
    Mesh m;
    m.finish = {{0.8, 0.75, 0.55}, 0.2, 30, 0.75};
    const double h = 1.6;
    tetrahedra(m,
               {Vec{0, h, 0}, Vec{-0.92, 0.01, -0.53}, Vec{0.92, 0.01, -0.53}, Vec{0, 0.01, 1.06}},
               static_cast<int>(std::min(levels, 9L)));
    scene.meshes.push_back(std::move(m));
    return scene;
}

// A fractal mountain (midpoint displacement on a square grid of 2^levels + 1 points a side,
// COUNT the level count) as one mesh, with reflective spheres resting round it, in the
// spirit of the SPD's "mount" (whose spheres are glass: rt's glass has no exact POV-Ray
// twin here, so these mirror).
Scene mountain(long levels, int size) {
    Scene scene = lit_scene(3, camera({0, 4.5, -9}, {0, 1.2, 0}, 50, size),
                            {{0.45, 0.5, 0.55}, 0.1, 10, 0.8});
    const int n = 1 << static_cast<int>(std::min(levels, 11L));
    const std::size_t side = static_cast<std::size_t>(n) + 1;
    std::vector<double> height(side * side, 0);
    Random random(5);
    const auto at = [&](std::size_t i, std::size_t j) -> double& { return height[i * side + j]; };
    double spread = 1.6;
    for (std::size_t step = static_cast<std::size_t>(n); step > 1; step /= 2, spread *= 0.55) {
        const std::size_t half = step / 2;
        for (std::size_t i = half; i < side; i += step)
            for (std::size_t j = half; j < side; j += step)
                at(i, j) = 0.25 * (at(i - half, j - half) + at(i - half, j + half) +
                                   at(i + half, j - half) + at(i + half, j + half)) +
                           random.uniform(-spread, spread);
        for (std::size_t i = 0; i < side; i += half)
            for (std::size_t j = (i / half) % 2 == 0 ? half : 0; j < side; j += step) {
                double sum = 0;
                int terms = 0;
                if (i >= half) sum += at(i - half, j), ++terms;
                if (i + half < side) sum += at(i + half, j), ++terms;
                if (j >= half) sum += at(i, j - half), ++terms;
                if (j + half < side) sum += at(i, j + half), ++terms;
                at(i, j) = sum / terms + random.uniform(-spread, spread);
            }
    }
    Mesh m;
    m.finish = {{0.55, 0.5, 0.4}, 0.05, 10, 0.9};
    const double extent = 6;
    for (std::size_t i = 0; i < side; ++i)
        for (std::size_t j = 0; j < side; ++j) {
            const double x = extent * (static_cast<double>(i) / n - 0.5);
            const double z = extent * (static_cast<double>(j) / n - 0.5);
            // A dome under the noise, so the mountain rises from the floor.
            const double dome = 2.2 * std::max(0.0, 1 - (x * x + z * z) / 9);
            m.vertices.push_back({x, std::max(0.02, dome + 0.5 * at(i, j)), z});
        }
    for (std::size_t i = 0; i + 1 < side; ++i)
        for (std::size_t j = 0; j + 1 < side; ++j) {
            const std::size_t a = i * side + j, b = a + 1, c = a + side + 1, d = a + side;
            m.triangles.push_back({a, b, c});
            m.triangles.push_back({a, c, d});
        }
    scene.meshes.push_back(std::move(m));
    Group balls{{{0.9, 0.95, 1}, 0.7, 120, 0.2}, {}};
    for (int k = 0; k < 4; ++k) {
        const double angle = std::numbers::pi * (0.2 + 0.4 * k);
        balls.spheres.push_back({{3.6 * std::cos(angle), 0.5, -3.6 * std::sin(angle) + 0.5}, 0.5});
    }
    scene.groups.push_back(std::move(balls));
    return scene;
}

// A frame (two unit vectors perpendicular to each other and to `normal`).
std::array<Vec, 2> frame_round(Vec normal) {
    const Vec side = normalized(std::fabs(normal.x) < 0.9 ? cross(normal, {1, 0, 0})
                                                          : cross(normal, {0, 1, 0}));
    return {side, cross(normal, side)};
}

// COUNT items on a square grid over the floor, `spacing` apart, seen from the front and
// above, looking at height `look_y`, with `finishes` seeded random finishes as its groups.
struct GridScene {
    Scene scene;
    long side = 1;
    double spacing = 1, extent = 0;
    // Item n's place on the grid, at height y.
    Vec point(long n, double y) const {
        return {static_cast<double>(n / side) * spacing - extent, y,
                static_cast<double>(n % side) * spacing - extent};
    }
};

GridScene grid_scene(long count, double spacing, double look_y, int size, Random& random,
                     long finishes) {
    GridScene grid;
    grid.side = std::max(1L, std::lround(std::ceil(std::sqrt(static_cast<double>(count)))));
    grid.spacing = spacing;
    grid.extent = spacing * static_cast<double>(grid.side - 1) / 2;
    grid.scene = lit_scene(
        3, camera({0, grid.extent + 4, -1.3 * grid.extent - 5}, {0, look_y, 0}, 50, size),
        {{0.5, 0.5, 0.55}, 0.2, 20, 0.7});
    for (long g = 0; g < finishes; ++g) grid.scene.groups.push_back({random_finish(random), {}});
    return grid;
}

// Chain-mail rings in the spirit of the SPD's "rings": COUNT rings on a square grid over the
// floor, each a circle of twelve open cylinders with a sphere at every joint, tilted by a
// seeded random angle so that neighbours interlock. Long thin overlapping boxes.
Scene rings(long count, int size) {
    Random random(6);
    constexpr long kFinishes = 6;
    GridScene grid = grid_scene(count, 1.7, 0.5, size, random, kFinishes);
    Scene& scene = grid.scene;
    constexpr int kSegments = 12;
    constexpr double kRadius = 1, kTube = 0.1;
    for (long n = 0; n < count; ++n) {
        const long i = n / grid.side, j = n % grid.side;
        const Vec centre = grid.point(n, kRadius + 0.3);
        const double tilt = random.uniform(0.5, 1.1) * ((i + j) % 2 == 0 ? 1 : -1);
        const double turn = random.uniform(0, std::numbers::pi);
        const Vec normal{std::sin(tilt) * std::cos(turn), std::cos(tilt),
                         std::sin(tilt) * std::sin(turn)};
        // Plain variables: clang 14 cannot capture structured bindings in a lambda.
        const std::array<Vec, 2> frame = frame_round(normal);
        const Vec u = frame[0], v = frame[1];
        Group& group = scene.groups[static_cast<std::size_t>(n % kFinishes)];
        for (int k = 0; k < kSegments; ++k) {
            const auto at = [&](int m) {
                const double a = 2 * std::numbers::pi * m / kSegments;
                return centre + kRadius * (std::cos(a) * u + std::sin(a) * v);
            };
            group.spheres.push_back({at(k), kTube});
            group.cylinders.push_back({at(k), at(k + 1) - at(k), kTube});
        }
    }
    return std::move(grid.scene);
}

// A cubic lattice of COUNT nodes a side: a sphere at every node and an open cylinder along
// every edge between neighbours (COUNT^3 spheres, 3 COUNT^2 (COUNT - 1) cylinders), shiny,
// seen from a corner, so that rays pass many rods' boxes before they hit one.
Scene lattice(long count, int size) {
    const long n = std::min(count, 200L);
    const double step = 3.0 / static_cast<double>(std::max(1L, n - 1));
    Scene scene = lit_scene(3, camera({3.6, 4.4, -4.2}, {0, 1.7, 0}, 45, size),
                            {{0.5, 0.55, 0.6}, 0.15, 10, 0.8});
    Group nodes{{{0.9, 0.75, 0.35}, 0.5, 60, 0.5}, {}};
    Group rods{{{0.6, 0.65, 0.75}, 0.3, 30, 0.7}, {}};
    const double rod = 0.06 * step, ball = 0.14 * step;
    const auto node = [&](long i, long j, long k) {
        return Vec{static_cast<double>(i) * step - 1.5, static_cast<double>(j) * step + 0.2,
                   static_cast<double>(k) * step - 1.5};
    };
    for (long i = 0; i < n; ++i)
        for (long j = 0; j < n; ++j)
            for (long k = 0; k < n; ++k) {
                const Vec p = node(i, j, k);
                nodes.spheres.push_back({p, ball});
                if (i + 1 < n) rods.cylinders.push_back({p, node(i + 1, j, k) - p, rod});
                if (j + 1 < n) rods.cylinders.push_back({p, node(i, j + 1, k) - p, rod});
                if (k + 1 < n) rods.cylinders.push_back({p, node(i, j, k + 1) - p, rod});
            }
    scene.groups.push_back(std::move(nodes));
    scene.groups.push_back(std::move(rods));
    return scene;
}

// Gears in the spirit of the SPD's "gears": COUNT gears on a grid, standing at seeded random
// angles, each a slab whose two faces are concave polygons of 24 teeth (96 vertices) and
// whose sides are 96 four-sided polygons. Large concave polygons with big, mostly empty boxes.
Scene gears(long count, int size) {
    Random random(7);
    constexpr long kFinishes = 5;
    GridScene grid = grid_scene(count, 2.3, 0.8, size, random, kFinishes);
    Scene& scene = grid.scene;
    constexpr int kTeeth = 24;
    constexpr double kOuter = 1, kInner = 0.82, kThickness = 0.2;
    for (long n = 0; n < count; ++n) {
        const Vec centre = grid.point(n, kOuter + 0.1);
        const double turn = random.uniform(0, std::numbers::pi);
        const double lean = random.uniform(-0.4, 0.4);
        // The gear's axis, lying nearly flat: the gear stands on its rim.
        const Vec axis = normalized({std::cos(turn), std::sin(lean), std::sin(turn)});
        const auto [u, v] = frame_round(axis);
        // Four vertices per tooth: root, flank up, top, flank down.
        std::vector<std::array<double, 2>> outline;
        for (int t = 0; t < kTeeth; ++t)
            for (int q = 0; q < 4; ++q) {
                const double a = 2 * std::numbers::pi * (t + q / 4.0) / kTeeth;
                const double r = q == 0 || q == 3 ? kInner : kOuter;
                outline.push_back({r * std::cos(a), r * std::sin(a)});
            }
        const Vec front = centre + 0.5 * kThickness * axis;
        const Vec back = centre - 0.5 * kThickness * axis;
        Group& group = scene.groups[static_cast<std::size_t>(n % kFinishes)];
        group.polygons.push_back({front, u, v, outline});
        group.polygons.push_back({back, u, v, {outline.rbegin(), outline.rend()}});
        const auto at = [&](std::size_t k) { return outline[k % outline.size()]; };
        for (std::size_t k = 0; k < outline.size(); ++k) {
            const Vec a = back + at(k)[0] * u + at(k)[1] * v;
            const Vec b = back + at(k + 1)[0] * u + at(k + 1)[1] * v;
            group.polygons.push_back({a, b - a, front - back, {{0, 0}, {1, 0}, {1, 1}, {0, 1}}});
        }
    }
    return std::move(grid.scene);
}

// Vectors as rt writes them, "x y z", and as POV-Ray does, "<x, y, z>".
std::ostream& operator<<(std::ostream& out, Vec a) {
    return out << a.x << ' ' << a.y << ' ' << a.z;
}
struct Pov {
    Vec v;
};
std::ostream& operator<<(std::ostream& out, Pov p) {
    return out << '<' << p.v.x << ", " << p.v.y << ", " << p.v.z << '>';
}

// A finish as rt's simple surface (ID 100) and as a POV-Ray texture.
struct RtSurface {
    const Finish& f;
};
std::ostream& operator<<(std::ostream& out, RtSurface s) {
    return out << "100  " << s.f.colour << "  " << s.f.ks << ' ' << s.f.ke << ' ' << s.f.kd
               << " 0 1";
}
struct PovTexture {
    const Finish& f;
};
std::ostream& operator<<(std::ostream& out, PovTexture t) {
    const Finish& f = t.f;
    return out << "texture { pigment { rgb " << Pov{f.colour} << " } finish { ambient " << f.kd
               << " diffuse " << f.kd << " phong " << f.ks << " phong_size " << f.ke
               << " reflection " << f.ks << " } }";
}

void write_rt(std::ostream& out, const Scene& s) {
    out << "# " << s.name << ": generated by rt_bench_scenes. Render with: rt -d " << s.depth
        << "\n";
    const Camera& c = s.camera;
    out << "102  " << c.eye << "  " << c.look_at << "  " << c.x << "  " << c.y << "  " << c.xres
        << ' ' << c.yres << "\n";
    out << "103  " << s.ambient << "\n";
    for (const Light& l : s.lights) out << "104  " << l.position << "  " << l.intensity << "\n";
    for (const Plane& p : s.planes)
        out << "2  " << p.offset << "  " << p.normal << "  " << RtSurface{p.finish} << "\n";
    for (const Group& g : s.groups) {
        out << "105  " << RtSurface{g.finish} << "\n";
        for (const Sphere& sp : g.spheres) out << "1 " << sp.radius << ' ' << sp.centre << " 106\n";
        for (const Cylinder& cyl : g.cylinders)
            out << "9 " << cyl.radius << " 0 1  " << cyl.base << "  " << cyl.axis << " 106\n";
        for (const Polygon& p : g.polygons) {
            out << "11 " << p.points.size();
            for (std::size_t k = 0; k < p.points.size(); ++k) out << "  " << p.vertex(k);
            out << " 106\n";
        }
    }
    for (const Mesh& m : s.meshes) {
        out << "14  " << m.vertices.size() << ' ' << m.triangles.size() << "\n";
        for (const Vec& p : m.vertices) out << p << "\n";
        for (const auto& t : m.triangles) out << t[0] << ' ' << t[1] << ' ' << t[2] << "\n";
        out << RtSurface{m.finish} << "\n";
    }
}

void write_pov(std::ostream& out, const Scene& s) {
    out << "// " << s.name << ": generated by rt_bench_scenes, the POV-Ray 3.7 equivalent of "
        << s.name << ".in rendered with rt -d " << s.depth << "\n#version 3.7;\n";
    out << "global_settings { assumed_gamma 1 max_trace_level " << s.depth + 1
        << " adc_bailout 0.01 ambient_light rgb " << Pov{s.ambient} << " }\n";
    out << "background { rgb " << Pov{s.ambient} << " }\n";
    // Shifted by half a pixel so that POV-Ray's pixel centres fall on rt's pixel corners.
    const Camera& c = s.camera;
    const Vec direction =
        normalized(c.look_at - c.eye) - (1.0 / c.xres) * c.x + (1.0 / c.yres) * c.y;
    out << "camera { perspective location " << Pov{c.eye} << " direction " << Pov{direction}
        << " right " << Pov{2 * c.x} << " up " << Pov{2 * c.y} << " }\n";
    for (const Light& l : s.lights)
        out << "light_source { " << Pov{l.position} << " color rgb " << Pov{l.intensity} << " }\n";
    for (const Plane& p : s.planes)
        out << "plane { " << Pov{p.normal} << ", " << p.offset << ' ' << PovTexture{p.finish}
            << " }\n";
    for (std::size_t i = 0; i < s.groups.size(); ++i) {
        out << "#declare T" << i << " = " << PovTexture{s.groups[i].finish} << ";\n";
        for (const Sphere& sp : s.groups[i].spheres)
            out << "sphere { " << Pov{sp.centre} << ", " << sp.radius << " texture { T" << i
                << " } }\n";
        for (const Cylinder& cyl : s.groups[i].cylinders)
            out << "cylinder { " << Pov{cyl.base} << ", " << Pov{cyl.base + cyl.axis} << ", "
                << cyl.radius << " open texture { T" << i << " } }\n";
        // POV-Ray's polygon is closed by repeating its first vertex; both use even-odd.
        for (const Polygon& p : s.groups[i].polygons) {
            out << "polygon { " << p.points.size() + 1;
            for (const auto& q : p.points) out << ", <" << q[0] << ", " << q[1] << '>';
            const Vec w = cross(p.u, p.v);
            out << ", <" << p.points[0][0] << ", " << p.points[0][1] << "> matrix <" << p.u.x
                << ", " << p.u.y << ", " << p.u.z << ", " << p.v.x << ", " << p.v.y << ", "
                << p.v.z << ", " << w.x << ", " << w.y << ", " << w.z << ", " << p.origin.x
                << ", " << p.origin.y << ", " << p.origin.z << "> texture { T" << i << " } }\n";
        }
    }
    for (const Mesh& m : s.meshes) {
        out << "mesh2 {\n  vertex_vectors { " << m.vertices.size();
        for (const Vec& p : m.vertices) out << ",\n" << Pov{p};
        out << " }\n  face_indices { " << m.triangles.size();
        for (const auto& t : m.triangles)
            out << ",\n<" << t[0] << ", " << t[1] << ", " << t[2] << '>';
        out << " }\n  " << PovTexture{m.finish} << "\n}\n";
    }
}

// "10k" is 10000, "1m" a million; at most 100 million.
long parse_count(const std::string& text) {
    constexpr long kMaxCount = 100'000'000;
    std::size_t used = 0;
    const long count = std::stol(text, &used);
    const std::string suffix = text.substr(used);
    const long scale = suffix == "k" ? 1000 : suffix == "m" ? 1000000 : suffix.empty() ? 1 : 0;
    if (scale == 0 || count < 1 || count > kMaxCount / scale)
        throw std::invalid_argument("bad count " + text);
    return count * scale;
}

Scene make_scene(const std::string& name, int size) {
    const std::size_t dash = name.find('-');
    const std::string kind = name.substr(0, dash);
    if (dash == std::string::npos) throw std::invalid_argument("no count");
    const long count = parse_count(name.substr(dash + 1));
    Scene scene = kind == "spheres"       ? spheres(count, size)
                  : kind == "mesh"        ? mesh(count, size)
                  : kind == "mirror"      ? mirror(count, size)
                  : kind == "sphereflake" ? sphereflake(count, size)
                  : kind == "shells"      ? shells(count, size)
                  : kind == "tetra"       ? tetra(count, size)
                  : kind == "mountain"    ? mountain(count, size)
                  : kind == "rings"       ? rings(count, size)
                  : kind == "lattice"     ? lattice(count, size)
                  : kind == "gears"       ? gears(count, size)
                                          : throw std::invalid_argument("unknown kind");
    scene.name = name;
    return scene;
}

void write_file(const std::filesystem::path& path, const Scene& scene,
                void (*write)(std::ostream&, const Scene&)) {
    std::ofstream out(path);
    out.precision(7);  // plenty for both formats, and keeps the files small
    write(out, scene);
    out.close();
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

int usage() {
    std::cerr << "usage: rt_bench_scenes [--size N] DIR [SCENE ...]\n"
                 "  SCENE: spheres-COUNT, mesh-COUNT, mirror-COUNT, shells-COUNT, rings-COUNT,\n"
                 "  gears-COUNT, lattice-SIDE, or sphereflake-LEVELS, tetra-LEVELS,\n"
                 "  mountain-LEVELS; COUNT may end in k or m\n";
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    int size = 1024;
    std::filesystem::path dir;
    std::vector<std::string> names;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--size" && i + 1 < argc) {
            size = std::atoi(argv[++i]);
            if (size < 1 || size > 16384) return usage();
        } else if (arg.starts_with("-")) {
            return usage();
        } else if (dir.empty()) {
            dir = arg;
        } else {
            names.push_back(arg);
        }
    }
    if (dir.empty()) return usage();
    if (names.empty())
        names = {"spheres-10k", "spheres-100k", "spheres-1m", "mesh-500k", "mirror-49"};
    try {
        std::filesystem::create_directories(dir);
        for (const std::string& name : names) {
            Scene scene;
            try {
                scene = make_scene(name, size);
            } catch (const std::logic_error&) {
                std::cerr << "rt_bench_scenes: bad scene name '" << name << "'\n";
                return usage();
            }
            write_file(dir / (name + ".in"), scene, write_rt);
            write_file(dir / (name + ".pov"), scene, write_pov);
        }
    } catch (const std::exception& e) {
        std::cerr << "rt_bench_scenes: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
