// The Wavefront OBJ reader (mesh from a file, ID 15) on fixtures written here: the four face
// forms, negative indices, fans, weights and colours, continuations, ignored statements noted
// once, corner normals turned into vertex normals, and every hostile case with its message
// and place (file:line:col).
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "check.h"
#include "rt/error.h"
#include "scene/mesh_file.h"

using namespace rt;
using namespace rt_test;

namespace {

using Triangle = std::array<std::uint32_t, 3>;
using Triangles = std::vector<Triangle>;
using Points = std::vector<Vec3>;
using Notes = std::vector<std::string>;

MeshFile obj(const std::string& text) { return read_obj(text, "t.obj"); }

const std::string kSquare = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
const std::string kThree = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
const std::string kStatement =
    "expected an OBJ statement (v, vn, vt, f, o, g, s, usemtl, mtllib, l, p, ...), found ";

}  // namespace

TEST(the_four_face_forms) {
    const std::string data = kSquare + "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n";
    const Triangles square = {{0, 1, 2}, {0, 2, 3}};
    MeshFile m = obj(data + "f 1 2 3 4\n");
    CHECK(m.positions == (Points{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}));
    CHECK(m.triangles == square);
    CHECK(m.normals.empty());
    m = obj(data + "f 1/1 2/2 3/3 4/4\n");
    CHECK(m.triangles == square);
    CHECK(m.normals.empty());
    CHECK(m.notes == (Notes{"OBJ texture coordinates (vt) ignored",
                            "OBJ texture-coordinate indices ignored"}));
    m = obj(data + "f 1//1 2//1 3//1 4//1\n");
    CHECK(m.triangles == square);
    CHECK(m.normals == (Points(4, Vec3{0, 0, 1})));
    m = obj(data + "f 1/4/1 2/3/1 3/2/1 4/1/1\n");
    CHECK(m.triangles == square);
    CHECK(m.normals == (Points(4, Vec3{0, 0, 1})));
    CHECK_EQ(m.positions.size(), 4u);
}

TEST(polygons_are_fans_from_their_first_vertex) {
    std::string text;
    for (int i = 0; i < 6; ++i) text += join("v ", i, " 0 0\n");
    const MeshFile m = obj(text + "f 1 2 3 4 5 6\nf 6 5 4 3\n");
    CHECK(m.triangles ==
          (Triangles{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {5, 4, 3}, {5, 3, 2}}));
}

TEST(negative_indices_count_back_from_the_last_so_far) {
    const MeshFile m = obj(kThree + "vn 1 0 0\nf -3//-1 -2//-1 -1//-1\nv 5 5 5\nvn 0 1 0\n" +
                           "f -4//-1 -1//-1 -2//1\n");
    CHECK(m.triangles == (Triangles{{0, 1, 2}, {4, 3, 2}}));
    // Vertex 0 has two normals: the second use becomes a copy of it, vertex 4.
    CHECK(m.positions == (Points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}, {0, 0, 0}}));
    CHECK(m.normals == (Points{{1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 1, 0}}));
    // Positive and negative spellings of one index, with '+'.
    CHECK(obj(kThree + "f +1 -2 3\n").triangles == (Triangles{{0, 1, 2}}));
}

TEST(corner_normals_become_vertex_normals) {
    // Normal 3 repeats normal 1's value: corners naming it share the vertex. Normal 2
    // differs: position 1 gets a copy (4) for its corners with normal 2, used twice.
    const std::string text = kSquare + "v 9 9 9\nvn 0 0 1\nvn 0 0.5 0.5\nvn 0 0 1\n" +
                             "f 1//1 2//1 3//1\nf 1//2 3//3 4//2\nf 1//2 4//2 2//1\n";
    const MeshFile m = obj(text);
    CHECK(m.positions ==
          (Points{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {9, 9, 9}, {0, 0, 0}}));
    // The unused vertex 4 has the zero normal.
    CHECK(m.normals ==
          (Points{{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0.5, 0.5}, {0, 0, 0}, {0, 0.5, 0.5}}));
    CHECK(m.triangles == (Triangles{{0, 1, 2}, {5, 2, 3}, {5, 3, 1}}));
    CHECK(m.notes.empty());
}

TEST(corners_without_normals_get_the_zero_normal) {
    const MeshFile m = obj(kSquare + "vn 0 0 1\nf 1//1 2//1 3//1\nf 1 3 4\n");
    // Positions 0 and 2 are named with a normal first, then without: each gets a copy whose
    // normal is zero, so the second triangle has no vertex normals at all.
    CHECK(m.positions ==
          (Points{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0}, {1, 1, 0}}));
    CHECK(m.normals == (Points{{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}}));
    CHECK(m.triangles == (Triangles{{0, 1, 2}, {4, 5, 3}}));
    CHECK(m.notes == Notes{"OBJ face corners without a normal: their triangles have no vertex "
                           "normals (flat in mode 0, computed in mode 2)"});
    // Within one face too: the corners without one share the zero normal.
    const MeshFile one = obj(kSquare + "vn 0 0 1\nf 1//1 2 3\n");
    CHECK(one.normals == (Points{{0, 0, 1}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}}));
    CHECK(one.triangles == (Triangles{{0, 1, 2}}));
}

TEST(numbers_as_written) {
    const MeshFile m =
        obj("v +1 +.5 -2e+1\nv 0.1 -0.30000000000000004 1e-310\nv 1.7976931348623157e308 -0 3\n"
            "vn +0.25 -1E2 .125\nf 1//1 2//1 3//1\n");
    CHECK(m.positions ==
          (Points{
              {1, 0.5, -20}, {0.1, -0.30000000000000004, 1e-310}, {1.7976931348623157e308, 0, 3}}));
    CHECK(m.normals == (Points(3, Vec3{0.25, -100, 0.125})));
}

TEST(weights_and_colours_are_ignored_and_noted_once) {
    const MeshFile m =
        obj("v 1 2 3 0.5\nv 4 5 6 0.1 0.2 0.3\nv 7 8 9 0.1 0.2 0.3 1\nv 1 1 1\nf 1 2 3\n");
    CHECK(m.positions == (Points{{1, 2, 3}, {4, 5, 6}, {7, 8, 9}, {1, 1, 1}}));
    CHECK(m.notes == Notes{"OBJ vertex weights and colours ignored"});
}

TEST(line_continuations_join_lines) {
    const MeshFile m =
        obj("v 1 \\\n2 3\nv 4\\\r\n 5 \\\r6\nv \\\n\\\n 7 8 9\ng a \\\n b\nf 1 2 \\\n3\n"
            "usemtl x\\\nf 3 2 1\n");
    CHECK(m.positions == (Points{{1, 2, 3}, {4, 5, 6}, {7, 8, 9}}));
    // The continued usemtl line swallows the face after it.
    CHECK(m.triangles == (Triangles{{0, 1, 2}}));
}

TEST(comments_blank_lines_and_line_ends) {
    for (const std::string eol : {"\n", "\r\n", "\r"}) {
        const std::string text = "# a comment" + eol + eol + "  \t" + eol + "v 0 0 0 # trailing" +
                                 eol + "\tv\t1 0 0" + eol + "   # indented" + eol + "v 0 1 0#" +
                                 eol + "f 1 2 3#c" + eol;
        const MeshFile m = obj(text);
        CHECK(m.positions == (Points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
        CHECK(m.triangles == (Triangles{{0, 1, 2}}));
        CHECK(m.notes.empty());
    }
    // A byte-order mark; no final line end.
    CHECK_EQ(obj("\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3").triangles.size(), 1u);
    // Nothing at all.
    const MeshFile empty = obj("");
    CHECK(empty.positions.empty() && empty.triangles.empty() && empty.notes.empty());
}

TEST(ignored_statements_are_noted_once_each) {
    const std::string text =
        "mtllib a.mtl\no thing\ng group one\ns 1\nusemtl red\n" + kThree +
        "vt 0 0\nvt 1 0 0\nl 1 2\np 1\ncstype bspline\ns off\ng other\nusemtl blue\no two\n"
        "mtllib b.mtl c.mtl\nl 2 3\np 2\nvp 0.5\ncstype bezier\nf 1/2 2/1 3/1\n";
    const MeshFile m = obj(text);
    CHECK(m.triangles == (Triangles{{0, 1, 2}}));
    CHECK(m.notes ==
          (Notes{"OBJ material libraries (mtllib) ignored", "OBJ object names (o) ignored",
                 "OBJ groups (g) ignored", "OBJ smoothing groups (s) ignored",
                 "OBJ materials (usemtl) ignored", "OBJ texture coordinates (vt) ignored",
                 "OBJ lines (l) ignored", "OBJ points (p) ignored",
                 "OBJ 'cstype' statements ignored (rt reads polygons only)",
                 "OBJ 'vp' statements ignored (rt reads polygons only)",
                 "OBJ texture-coordinate indices ignored"}));
}

TEST(read_mesh_file_reads_obj) {
    const MeshFile m = read_mesh_file(kThree + "f 1 2 3\n", "t.obj");
    CHECK(m.triangles == (Triangles{{0, 1, 2}}));
}

TEST(statement_errors_name_line_and_column) {
    CHECK_ERROR(obj("v 0 0 0\nfoo 1 2\n"), "t.obj:2:1: " + kStatement + "'foo'");
    CHECK_ERROR(obj("vertex 0 0 0\n"), "t.obj:1:1: " + kStatement + "'vertex'");
    CHECK_ERROR(obj("v 1 2\n"), "t.obj:1:6: expected a coordinate (z), found the end of the line");
    CHECK_ERROR(obj("v 1 2"), "t.obj:1:6: expected a coordinate (z), found the end of the file");
    CHECK_ERROR(obj("v 1 2 # z\n"), "t.obj:1:7: expected a coordinate (z), found a comment");
    CHECK_ERROR(obj("v 1 2 nan\n"), "t.obj:1:7: expected a coordinate (z), found 'nan'");
    CHECK_ERROR(obj("v 1 inf 2\n"), "t.obj:1:5: expected a coordinate (y), found 'inf'");
    CHECK_ERROR(obj("v 1 2 -1e400\n"), "t.obj:1:7: expected a coordinate (z), found '-1e400'");
    CHECK_ERROR(obj("v 1 2 3abc\n"), "t.obj:1:7: expected a coordinate (z), found '3abc'");
    CHECK_ERROR(obj("v +-1 2 3\n"), "t.obj:1:3: expected a coordinate (x), found '+-1'");
    CHECK_ERROR(obj("v + 1 2 3\n"), "t.obj:1:3: expected a coordinate (x), found '+'");
    CHECK_ERROR(obj("v 1 2 3 x\n"),
                "t.obj:1:9: expected a number (a weight or a colour) or the end of the line, "
                "found 'x'");
    CHECK_ERROR(obj("v 1 2 3 4 5 6 7 8\n"), "t.obj:1:17: expected the end of the line, found '8'");
    CHECK_ERROR(obj("v 1 2 3 # c\nvn 1 2 3 4\n"),
                "t.obj:2:10: expected the end of the line, found '4'");
    CHECK_ERROR(obj("vn 1 nan 0\n"), "t.obj:1:6: expected a normal component (y), found 'nan'");
    // Places count physical lines, whatever ends them, continuations included.
    CHECK_ERROR(obj("v 0 0 0\rv 0 0 0\r\nv 1 2\r"),
                "t.obj:3:6: expected a coordinate (z), found the end of the line");
    CHECK_ERROR(obj("v 1 \\\n2\nv 1 2\n"),
                "t.obj:2:2: expected a coordinate (z), found the end of the line");
    // Hostile bytes are shown escaped.
    CHECK_ERROR(obj("\x1b]0;x\x07 1\n"), "t.obj:1:1: " + kStatement + "'\\x1b]0;x\\x07'");
}

TEST(face_errors_name_the_corner) {
    const auto face = [](const std::string& f) { return obj(kThree + f + "\n"); };
    CHECK_ERROR(face("f 1 2 4"),
                "t.obj:4:7: expected a vertex index from 1 to 3 or from -3 to -1, found '4'");
    CHECK_ERROR(face("f 1 2 0"),
                "t.obj:4:7: expected a vertex index from 1 to 3 or from -3 to -1, found '0'");
    CHECK_ERROR(face("f 1 2 -4"),
                "t.obj:4:7: expected a vertex index from 1 to 3 or from -3 to -1, found '-4'");
    CHECK_ERROR(face("f 1 2 4294967297"),
                "t.obj:4:7: expected a vertex index from 1 to 3 or from -3 to -1, found "
                "'4294967297'");
    CHECK_ERROR(face("f 1 2 99999999999999999999999"),
                "t.obj:4:7: expected a vertex index from 1 to 3 or from -3 to -1, found "
                "'99999999999999999999999'");
    CHECK_ERROR(face("f 1 2"), "t.obj:4:1: expected a face of at least 3 vertices, found 2");
    CHECK_ERROR(face("f"), "t.obj:4:1: expected a face of at least 3 vertices, found 0");
    CHECK_ERROR(face("f a b c"), "t.obj:4:3: expected a vertex index, found 'a'");
    CHECK_ERROR(face("f 1 2 3 +"), "t.obj:4:9: expected a vertex index, found '+'");
    CHECK_ERROR(face("f 1x 2 3"), "t.obj:4:4: expected '/' or the end of the corner, found 'x'");
    CHECK_ERROR(face("f 1/1 2 3"),
                "t.obj:4:5: expected a texture-coordinate index, found '1', but no texture "
                "coordinates are defined before this face");
    CHECK_ERROR(face("f 1//1 2//1 3//1"),
                "t.obj:4:6: expected a normal index, found '1', but no normals are defined before "
                "this face");
    CHECK_ERROR(face("f 1/ 2 3"),
                "t.obj:4:5: expected a texture-coordinate index, found white "
                "space");
    CHECK_ERROR(face("f 1//x 2 3"), "t.obj:4:6: expected a normal index, found 'x'");
    CHECK_ERROR(face("vt 0 0\nf 1/1/ 2 3"),
                "t.obj:5:7: expected a normal index, found white space");
    CHECK_ERROR(face("vt 0 0\nf 1/1x 2 3"),
                "t.obj:5:6: expected '/' or the end of the corner, found 'x'");
    CHECK_ERROR(face("vn 0 0 1\nf 1//1 2//2 3//1"),
                "t.obj:5:11: expected a normal index from 1 to 1 or from -1 to -1, found '2'");
    CHECK_ERROR(face("vt 0 0\nvn 0 0 1\nf 1/1/1/1 2 3"),
                "t.obj:6:8: expected the end of the corner, found '/1'");
    CHECK_ERROR(face("vn 0 0 1\nf 1//1x 2 3"),
                "t.obj:5:7: expected the end of the corner, found 'x'");
    // Indices name what is defined before the face, not after it.
    CHECK_ERROR(obj("f 1 2 3\n" + kThree),
                "t.obj:1:3: expected a vertex index, found '1', but no vertices are defined "
                "before this face");
}
