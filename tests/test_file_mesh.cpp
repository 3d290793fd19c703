// The mesh from a file (15): PLY and OBJ files render exactly as the same triangles written as
// a mesh (14) where they are flat and as a smooth mesh (16) where they carry normals, in every
// mode; the file is found relative to the scene, read once however it is spelled, listed as
// an input, refused when it is no regular file, and its errors name both places.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "check.h"
#include "cli_util.h"
#include "rt/render.h"
#include "rtpp/compiler.h"
#include "scene/mesh_file.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;
namespace fs = std::filesystem;

namespace {

const char* const kSetting =
    "102  0 0 4  0 0 0  0.4 0 0  0 0.4 0  24 24\n103 0 0 0\n104 4 5 6  1 1 1\n";
const char* const kSurface = "100  0.9 0.7 0.5  0.3 20 0.8 0 1\n";

struct Mesh {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;  // empty or one per position
    std::vector<std::array<int, 3>> triangles;
};

// A UV sphere of unit radius: `stacks` bands, `slices` around; each normal is its position.
Mesh uv_sphere(int stacks, int slices) {
    const double pi = std::acos(-1.0);
    Mesh m;
    m.positions.push_back({0, 1, 0});
    for (int i = 1; i < stacks; ++i)
        for (int j = 0; j < slices; ++j) {
            const double theta = pi * i / stacks, phi = 2 * pi * j / slices;
            m.positions.push_back({std::sin(theta) * std::cos(phi), std::cos(theta),
                                   -std::sin(theta) * std::sin(phi)});
        }
    m.positions.push_back({0, -1, 0});
    const int last = static_cast<int>(m.positions.size()) - 1;
    auto ring = [&](int i, int j) { return 1 + (i - 1) * slices + (j % slices); };
    for (int j = 0; j < slices; ++j) {
        m.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
        for (int i = 1; i + 1 < stacks; ++i) {
            m.triangles.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
            m.triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
        }
        m.triangles.push_back({last, ring(stacks - 1, j + 1), ring(stacks - 1, j)});
    }
    m.normals = m.positions;
    return m;
}

// A double rounded to float through memory: g++ 12.2 at -O2 drops the rounding of a loop
// that writes v.x = float(v.x) back in place (its SLP vectorizer takes the store for a no-op).
double to_float(double x) {
    volatile float f = static_cast<float>(x);
    return f;
}

// The mesh with every coordinate rounded to float, as a binary float PLY stores it.
Mesh as_floats(Mesh m) {
    const auto round = [](const Vec3& v) {
        return Vec3{to_float(v.x), to_float(v.y), to_float(v.z)};
    };
    for (Vec3& v : m.positions) v = round(v);
    for (Vec3& v : m.normals) v = round(v);
    return m;
}

std::ostream& operator<<(std::ostream& out, const Vec3& v) {
    return out << v.x << ' ' << v.y << ' ' << v.z;
}

// The mesh as scene text: ID 14 without normals, 16 with them.
std::string inline_mesh(const Mesh& m, bool smooth) {
    std::ostringstream out;
    out.precision(17);
    out << (smooth ? 16 : 14) << ' ' << m.positions.size() << ' ' << m.triangles.size() << '\n';
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        out << m.positions[i];
        if (smooth) out << "  " << m.normals[i];
        out << '\n';
    }
    for (const auto& t : m.triangles) out << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
    out << kSurface;
    return out.str();
}

std::string ascii_ply(const Mesh& m, bool normals) {
    std::ostringstream out;
    out.precision(17);
    out << "ply\nformat ascii 1.0\ncomment made by test_file_mesh\nelement vertex "
        << m.positions.size() << "\nproperty double x\nproperty double y\nproperty double z\n";
    if (normals) out << "property double nx\nproperty double ny\nproperty double nz\n";
    out << "element face " << m.triangles.size()
        << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        out << m.positions[i];
        if (normals) out << ' ' << m.normals[i];
        out << '\n';
    }
    for (const auto& t : m.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
    return out.str();
}

template <class T>
void put(std::string& out, T value, bool big) {
    auto bytes = std::bit_cast<std::array<char, sizeof(T)>>(value);
    if (big) std::reverse(bytes.begin(), bytes.end());
    out.append(bytes.data(), bytes.size());
}

// Float coordinates and normals, ushort counts, uint indices, in either byte order.
std::string binary_ply(const Mesh& m, bool big) {
    std::string out = "ply\nformat " +
                      std::string(big ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\nelement vertex " + std::to_string(m.positions.size()) +
                      "\nproperty float x\nproperty float y\nproperty float z\n"
                      "property float nx\nproperty float ny\nproperty float nz\n"
                      "element face " +
                      std::to_string(m.triangles.size()) +
                      "\nproperty list ushort uint vertex_indices\nend_header\n";
    for (std::size_t i = 0; i < m.positions.size(); ++i)
        for (const Vec3* v : {&m.positions[i], &m.normals[i]})
            for (double c : {v->x, v->y, v->z}) put(out, static_cast<float>(c), big);
    for (const auto& t : m.triangles) {
        put(out, std::uint16_t{3}, big);
        for (int k : t) put(out, static_cast<std::uint32_t>(k), big);
    }
    return out;
}

// OBJ with `v//vn` corners and negative indices for the normals, or plain `v` corners.
std::string obj(const Mesh& m, bool normals) {
    std::ostringstream out;
    out.precision(17);
    out << "# made by test_file_mesh\no sphere\n";
    for (const Vec3& p : m.positions) out << "v " << p << '\n';
    if (normals)
        for (const Vec3& n : m.normals) out << "vn " << n << '\n';
    const auto count = static_cast<int>(m.positions.size());
    for (const auto& t : m.triangles) {
        out << 'f';
        for (int k : t) {
            out << ' ' << k + 1;
            if (normals) out << "//" << k - count;
        }
        out << '\n';
    }
    return out.str();
}

struct Read {
    Scene scene;
    std::vector<SceneInput> inputs;
    std::size_t files_read = 0;
};

Read read_in(const fs::path& dir, const std::string& text) {
    std::istringstream in(text);
    SceneReader reader(in, "scene.in", dir);
    Read r{reader.read_scene(), reader.input_files(), reader.mesh_files_read()};
    r.scene.build_index();
    return r;
}

Raster render_in(const fs::path& dir, const std::string& text) {
    RenderOptions options;
    options.threads = 1;
    return render(read_in(dir, text).scene, options);
}

std::string error_in(const fs::path& dir, const std::string& text) {
    try {
        read_in(dir, text);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

std::string from_file(int mode, const std::string& path) {
    return "15 " + std::to_string(mode) + ' ' + path + ' ' + kSurface;
}

// At the caller's line, so that a failure says which comparison it was.
#define CHECK_SAME(a, b) CHECK(identical((a), (b)))

}  // namespace

TEST(a_ply_or_obj_without_normals_renders_as_the_mesh) {
    const fs::path dir = work_dir("file_mesh_flat");
    const Mesh m = uv_sphere(7, 11);
    write_file(dir / "flat.ply", ascii_ply(m, false));
    write_file(dir / "flat.obj", obj(m, false));
    const Raster expected = render_in(dir, kSetting + inline_mesh(m, false));
    for (const char* name : {"flat.ply", "flat.obj"})
        for (int mode : {0, 1})
            CHECK_SAME(render_in(dir, kSetting + from_file(mode, name)), expected);
}

TEST(normals_in_the_file_render_as_the_smooth_mesh_and_mode_1_ignores_them) {
    const fs::path dir = work_dir("file_mesh_smooth");
    const Mesh m = uv_sphere(7, 11);
    write_file(dir / "smooth.ply", ascii_ply(m, true));
    write_file(dir / "smooth.obj", obj(m, true));
    const Raster smooth = render_in(dir, kSetting + inline_mesh(m, true));
    const Raster flat = render_in(dir, kSetting + inline_mesh(m, false));
    CHECK(!identical(smooth, flat));
    for (const char* name : {"smooth.ply", "smooth.obj"}) {
        CHECK_SAME(render_in(dir, kSetting + from_file(0, name)), smooth);
        CHECK_SAME(render_in(dir, kSetting + from_file(2, name)), smooth);
        CHECK_SAME(render_in(dir, kSetting + from_file(1, name)), flat);
    }
}

TEST(binary_ply_in_both_byte_orders_renders_its_float_values) {
    const fs::path dir = work_dir("file_mesh_binary");
    const Mesh m = as_floats(uv_sphere(6, 9));
    write_file(dir / "le.ply", binary_ply(m, false));
    write_file(dir / "be.ply", binary_ply(m, true));
    const Raster expected = render_in(dir, kSetting + inline_mesh(m, true));
    CHECK_SAME(render_in(dir, kSetting + from_file(0, "le.ply")), expected);
    CHECK_SAME(render_in(dir, kSetting + from_file(0, "be.ply")), expected);
}

// An octahedron's angle-weighted vertex normals point along the axes, by symmetry: mode 2
// renders it as the smooth mesh with those normals written out.
TEST(mode_2_computes_angle_weighted_normals) {
    const fs::path dir = work_dir("file_mesh_computed");
    Mesh m;
    m.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    m.normals = m.positions;
    m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                   {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    write_file(dir / "octahedron.obj", obj(m, false));
    const Raster smooth = render_in(dir, kSetting + inline_mesh(m, true));
    CHECK_SAME(render_in(dir, kSetting + from_file(2, "octahedron.obj")), smooth);
    CHECK_SAME(render_in(dir, kSetting + from_file(0, "octahedron.obj")),
               render_in(dir, kSetting + inline_mesh(m, false)));
}

Mesh octahedron(const Vec3& centre, double radius) {
    Mesh m;
    for (const Vec3& axis : {Vec3{1, 0, 0}, Vec3{-1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, -1, 0},
                             Vec3{0, 0, 1}, Vec3{0, 0, -1}}) {
        m.positions.push_back(centre + radius * axis);
        m.normals.push_back(axis);
    }
    m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                   {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    return m;
}

// One OBJ, two octahedra: the left with a normal at every corner, the right with none.
// Mode 0 shades the left smooth and the right flat; mode 2 computes the right's normals.
TEST(an_obj_with_normals_on_some_faces_is_smooth_where_it_has_them) {
    const fs::path dir = work_dir("file_mesh_mixed");
    const Mesh left = octahedron({-0.6, 0, 0}, 0.5), right = octahedron({0.6, 0, 0}, 0.5);
    std::ostringstream file;
    file.precision(17);
    for (const Mesh* m : {&left, &right})
        for (const Vec3& p : m->positions) file << "v " << p << '\n';
    for (const Vec3& n : left.normals) file << "vn " << n << '\n';
    for (const auto& t : left.triangles)
        file << "f " << t[0] + 1 << "//" << t[0] + 1 << ' ' << t[1] + 1 << "//" << t[1] + 1 << ' '
             << t[2] + 1 << "//" << t[2] + 1 << '\n';
    for (const auto& t : right.triangles)
        file << "f " << t[0] + 7 << ' ' << t[1] + 7 << ' ' << t[2] + 7 << '\n';
    write_file(dir / "mixed.obj", file.str());
    CHECK_SAME(render_in(dir, kSetting + from_file(0, "mixed.obj")),
               render_in(dir, kSetting + inline_mesh(left, true) + inline_mesh(right, false)));
    // The computed normals are the axes, to rounding (the octahedron's symmetry), and the
    // image is the smooth mesh with exactly those.
    Mesh computed = right;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    for (const auto& t : right.triangles)
        triangles.push_back({static_cast<std::uint32_t>(t[0]), static_cast<std::uint32_t>(t[1]),
                             static_cast<std::uint32_t>(t[2])});
    computed.normals = angle_weighted_normals(right.positions, triangles);
    for (std::size_t i = 0; i < computed.normals.size(); ++i)
        CHECK(near(computed.normals[i], right.normals[i], 1e-15));
    CHECK_SAME(render_in(dir, kSetting + from_file(2, "mixed.obj")),
               render_in(dir, kSetting + inline_mesh(left, true) + inline_mesh(computed, true)));
}

TEST(polygons_are_fan_triangulated) {
    const fs::path dir = work_dir("file_mesh_polygons");
    write_file(dir / "quad.obj",
               "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nv 0 1.5 0\nf 1 2 3 5 4\n");
    write_file(dir / "quad.ply",
               "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
               "property float z\nelement face 1\nproperty list uchar int vertex_index\n"
               "end_header\n-1 -1 0\n1 -1 0\n1 1 0\n-1 1 0\n0 1.5 0\n5 0 1 2 4 3\n");
    const std::string fan = std::string("14 5 3  -1 -1 0  1 -1 0  1 1 0  -1 1 0  0 1.5 0  ") +
                            "0 1 2  0 2 4  0 4 3 " + kSurface;
    const Raster expected = render_in(dir, kSetting + fan);
    CHECK_SAME(render_in(dir, kSetting + from_file(0, "quad.obj")), expected);
    CHECK_SAME(render_in(dir, kSetting + from_file(0, "quad.ply")), expected);
}

TEST(the_file_is_read_once_and_every_spelling_is_an_input) {
    const fs::path dir = work_dir("file_mesh_once");
    fs::create_directories(dir / "models");
    write_file(dir / "models" / "s.ply", ascii_ply(uv_sphere(5, 7), true));
    fs::remove(dir / "link.ply");
    fs::create_symlink("models/s.ply", dir / "link.ply");
    // The absolute spelling resolves to the first; "./models" is another spelling.
    const Read r = read_in(dir, kSetting + from_file(0, "models/s.ply") +
                                    from_file(0, "./models/s.ply") + from_file(1, "link.ply") +
                                    from_file(0, (dir / "models" / "s.ply").string()));
    CHECK_EQ(r.files_read, 1u);
    CHECK_EQ(r.scene.objects.size(), 4u);
    // One shape per file and mode, shared by the objects that name it.
    CHECK(r.scene.objects[0].shape.data == r.scene.objects[1].shape.data);
    CHECK(r.scene.objects[0].shape.data == r.scene.objects[3].shape.data);
    CHECK(r.scene.objects[0].shape.data != r.scene.objects[2].shape.data);
    CHECK_EQ(r.inputs.size(), 3u);
    CHECK_EQ(r.inputs.front().path.string(), (dir / "models/s.ply").string());
    CHECK_EQ(std::string(r.inputs.front().role), "the mesh file");
    CHECK_EQ(r.inputs[2].path.string(), (dir / "link.ply").string());
}

TEST(what_the_file_held_and_rt_ignored_is_noted_once_each) {
    const fs::path dir = work_dir("file_mesh_notes");
    write_file(dir / "t.obj",
               "mtllib t.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\n"
               "f 1/1 2/2 3/1\nf 1/2 3/2 2/1\n");
    const Read r = read_in(dir, kSetting + from_file(0, "t.obj"));
    std::string notes;
    for (const std::string& n : r.scene.notes) notes += n + "\n";
    CHECK_CONTAINS(notes, (dir / "t.obj").string() + ": ");
    CHECK_CONTAINS(notes, "texture coordinates (vt) ignored");
    CHECK_CONTAINS(notes, "texture-coordinate indices ignored");
    CHECK_CONTAINS(notes, "(usemtl) ignored");
    CHECK_CONTAINS(notes, "(mtllib) ignored");
    CHECK_EQ(r.scene.notes.size(), 4u);
}

TEST(what_is_not_a_regular_file_is_refused_without_blocking) {
    const fs::path dir = work_dir("file_mesh_fifo");
    fs::remove(dir / "fifo.ply");
    CHECK_EQ(::mkfifo((dir / "fifo.ply").c_str(), 0600), 0);
    fs::create_directories(dir / "dir.ply");
    ::alarm(60);  // an open that blocks would otherwise hang the test for ever
    CHECK_CONTAINS(
        error_in(dir, kSetting + from_file(0, "fifo.ply")),
        "scene.in:4:6: cannot read mesh file 'fifo.ply': it is not a regular file (a FIFO)");
    CHECK_CONTAINS(error_in(dir, kSetting + from_file(0, "dir.ply")), "it is a directory");
    CHECK_CONTAINS(error_in(dir, kSetting + from_file(0, "none.obj")),
                   "cannot read mesh file 'none.obj': cannot open it: No such file or directory");
    CHECK_CONTAINS(error_in(dir, kSetting + from_file(0, "none.obj")),
                   "(looked for '" + (dir / "none.obj").string() + "')");
    ::alarm(0);
}

TEST(errors_name_the_scene_place_and_the_file_place) {
    const fs::path dir = work_dir("file_mesh_errors");
    write_file(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n");
    write_file(dir / "far.obj", "v 0 0 0\nv 1e200 0 0\nv 0 1 0\nf 1 2 3\n");
    write_file(dir / "flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    write_file(dir / "empty.obj", "v 0 0 0\n");
    const std::string bad = error_in(dir, kSetting + from_file(0, "bad.obj"));
    CHECK_CONTAINS(bad, "scene.in:4:6: cannot read mesh file 'bad.obj': ");
    CHECK_CONTAINS(bad, (dir / "bad.obj").string() + ":4:7: ");
    CHECK_CONTAINS(error_in(dir, kSetting + from_file(0, "far.obj")),
                   "vertex 1: a coordinate is beyond +-1e+100");
    CHECK_CONTAINS(error_in(dir, kSetting + from_file(0, "flat.obj")),
                   "no triangle with non-zero area (all 1 are degenerate)");
    CHECK_CONTAINS(error_in(dir, kSetting + from_file(0, "empty.obj")), "it has no faces");
    CHECK_CONTAINS(error_in(dir, kSetting + from_file(3, "bad.obj")), "scene.in:4:4: ");
    CHECK_CONTAINS(error_in(dir, std::string(kSetting) + "15 0\n"),
                   "scene.in:4:5: unexpected end of file: expected mesh file path");
}

TEST(zero_normals_in_a_file_shade_their_triangles_flat) {
    const fs::path dir = work_dir("file_mesh_zero_normals");
    Mesh m = uv_sphere(5, 7);
    for (Vec3& n : m.normals) n = {};
    write_file(dir / "zero.ply", ascii_ply(m, true));
    CHECK_SAME(render_in(dir, kSetting + from_file(0, "zero.ply")),
               render_in(dir, kSetting + inline_mesh(m, false)));
}

TEST(rt_never_writes_over_a_mesh_file_and_lists_it_for_make) {
    const fs::path dir = work_dir("file_mesh_cli");
    write_file(dir / "m.ply", ascii_ply(uv_sphere(4, 6), false));
    write_file(dir / "scene.in", std::string(kSetting) + from_file(0, "m.ply"));
    const std::string before = read_file(dir / "m.ply");
    const RunResult refused = run_rt(dir, "scene.in -f ppm -o m.ply");
    CHECK_EQ(refused.status, 1);
    CHECK_CONTAINS(refused.err, "it is the mesh file 'm.ply', which this render reads");
    CHECK(read_file(dir / "m.ply") == before);
    const RunResult made = run_rt(dir, "scene.in -o out.ppm -M out.d");
    CHECK_EQ(made.status, 0);
    CHECK_CONTAINS(read_file(dir / "out.d"), "m.ply");
}

TEST(rtpp_writes_a_mesh_file_object_that_renders_as_the_file) {
    const fs::path dir = work_dir("file_mesh_rtpp");
    fs::create_directories(dir / "models");
    const Mesh m = uv_sphere(6, 9);
    write_file(dir / "models" / "ball.ply", ascii_ply(m, true));
    // The path is resolved against the .rts file's directory and written relative to where
    // rtpp runs; transforms put the mesh in an affine.
    const std::string source =
        "camera { position <0, 0, 4> look_at <0, 0, 0> fov 45 size 24, 24 }\n"
        "point_light { position <4, 5, 6> intensity 1 }\n"
        "let matte = surface { colour <0.9, 0.7, 0.5> ks 0.3 ke 20 kd 0.8 }\n"
        "mesh_file { file \"ball.ply\" mode 1 surface matte scale 0.5 }\n"
        "mesh_file { file \"ball.ply\" surface matte translate <1, 0, 0> }\n";
    write_file(dir / "models" / "scene.rts", source);
    const std::string compiled =
        rtpp::compile(source, (dir / "models" / "scene.rts").string(), dir / "models");
    CHECK_CONTAINS(compiled, "15 1 \"" + (dir / "models" / "ball.ply").string() + "\"");
    CHECK_CONTAINS(compiled, "15 0 \"" + (dir / "models" / "ball.ply").string() + "\"");
    const Read r = read_in(dir, compiled);
    CHECK_EQ(r.scene.objects.size(), 2u);
    CHECK_EQ(r.files_read, 1u);
    CHECK_EQ(r.scene.objects[0].shape.type->id, 7);
}
