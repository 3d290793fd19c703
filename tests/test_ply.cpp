// The PLY reader (mesh from a file, ID 15) on fixtures written here: every scalar type in all
// three formats giving exactly the values written, fans, skipped properties and elements,
// header spellings and line ends, every hostile case with its message and place; and the
// angle-weighted vertex normals against closed forms.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "check.h"
#include "rt/error.h"
#include "scene/mesh_file.h"

using namespace rt;
using namespace rt_test;

namespace {

using Triangle = std::array<std::uint32_t, 3>;

enum class Order { kAscii, kLittle, kBig };
constexpr Order kOrders[] = {Order::kAscii, Order::kLittle, Order::kBig};

const char* format_name(Order order) {
    return order == Order::kAscii    ? "ascii"
           : order == Order::kLittle ? "binary_little_endian"
                                     : "binary_big_endian";
}

// One value of a record, with the PLY type it is written as.
struct Value {
    template <typename T>
    Value(std::string type_, T value_)
        : type(std::move(type_)), value(static_cast<double>(value_)) {}
    std::string type;
    double value;
};
using Record = std::vector<Value>;

const char* const kTypes[] = {"char",  "uchar",  "short",   "ushort", "int",   "uint",
                              "float", "double", "int8",    "uint8",  "int16", "uint16",
                              "int32", "uint32", "float32", "float64"};
const char* const kIntegerTypes[] = {"char", "uchar", "short", "ushort", "int",   "uint",
                                     "int8", "uint8", "int16", "uint16", "int32", "uint32"};

bool is_float_type(const std::string& t) {
    return t == "float" || t == "double" || t == "float32" || t == "float64";
}

template <typename T>
void put(std::string& out, T v, bool big) {
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, &v, sizeof(T));
    if (big != (std::endian::native == std::endian::big)) std::reverse(raw, raw + sizeof(T));
    out.append(reinterpret_cast<const char*>(raw), sizeof(T));
}

void put_binary(std::string& out, const Value& v, bool big) {
    const std::string& t = v.type;
    if (t == "char" || t == "int8") return put(out, static_cast<std::int8_t>(v.value), big);
    if (t == "uchar" || t == "uint8") return put(out, static_cast<std::uint8_t>(v.value), big);
    if (t == "short" || t == "int16") return put(out, static_cast<std::int16_t>(v.value), big);
    if (t == "ushort" || t == "uint16") return put(out, static_cast<std::uint16_t>(v.value), big);
    if (t == "int" || t == "int32") return put(out, static_cast<std::int32_t>(v.value), big);
    if (t == "uint" || t == "uint32") return put(out, static_cast<std::uint32_t>(v.value), big);
    if (t == "float" || t == "float32") return put(out, static_cast<float>(v.value), big);
    put(out, v.value, big);
}

std::string ascii_value(const Value& v) {
    if (is_float_type(v.type)) return join(v.value);
    return std::to_string(static_cast<long long>(v.value));
}

std::string header(Order order, const std::string& elements) {
    return join("ply\nformat ", format_name(order), " 1.0\n", elements, "end_header\n");
}

std::string body(Order order, const std::vector<Record>& records) {
    std::string s;
    for (const Record& r : records) {
        if (order == Order::kAscii) {
            for (std::size_t i = 0; i < r.size(); ++i) {
                if (i > 0) s += ' ';
                s += ascii_value(r[i]);
            }
            s += '\n';
        } else {
            for (const Value& v : r) put_binary(s, v, order == Order::kBig);
        }
    }
    return s;
}

std::string ply(Order order, const std::string& elements, const std::vector<Record>& records) {
    return header(order, elements) + body(order, records);
}

const std::string kXyzFloat = "property float x\nproperty float y\nproperty float z\n";
const std::string kFaceList = "element face 1\nproperty list uchar int vertex_indices\n";

// A triangle's vertices in float, then the face (0 1 2).
std::vector<Record> one_triangle() {
    return {{{"float", 0}, {"float", 0}, {"float", 0}},
            {{"float", 1}, {"float", 0}, {"float", 0}},
            {{"float", 0}, {"float", 1}, {"float", 0}},
            {{"uchar", 3}, {"int", 0}, {"int", 1}, {"int", 2}}};
}
const std::string kOneTriangleElements = "element vertex 3\n" + kXyzFloat + kFaceList;

bool same_triangles(const std::vector<Triangle>& a, const std::vector<Triangle>& b) {
    return a == b;
}

}  // namespace

TEST(every_scalar_type_for_coordinates_in_every_format) {
    for (const char* type : kTypes) {
        const std::string t = type;
        const bool is_float = is_float_type(t);
        const bool is_signed = is_float || t == "char" || t == "int8" || t == "short" ||
                               t == "int16" || t == "int" || t == "int32";
        // Values each type holds exactly, the extremes of the small types included.
        const std::vector<Vec3> points =
            is_float    ? std::vector<Vec3>{{0.375, -1.5, 1048576}, {-0.0078125, 3, 1e-3}}
            : is_signed ? std::vector<Vec3>{{-128, 127, 0}, {-5, 7, 100}}
                        : std::vector<Vec3>{{0, 255, 1}, {5, 7, 100}};
        for (const Order order : kOrders) {
            std::vector<Record> records;
            for (const Vec3& p : points) records.push_back({{t, p.x}, {t, p.y}, {t, p.z}});
            const std::string elements = join("element vertex 2\nproperty ", t, " x\nproperty ", t,
                                              " y\nproperty ", t, " z\n");
            const MeshFile m = read_ply(ply(order, elements, records), "t.ply");
            CHECK_EQ(m.positions.size(), 2u);
            for (std::size_t i = 0; i < m.positions.size() && i < 2; ++i) {
                Vec3 expected = points[i];
                // Binary float32 stores 1e-3 rounded to float; ASCII keeps the decimal.
                if ((t == "float" || t == "float32") && order != Order::kAscii)
                    expected = {static_cast<float>(expected.x), static_cast<float>(expected.y),
                                static_cast<float>(expected.z)};
                if (!(m.positions[i] == expected))
                    record_failure(__FILE__, __LINE__,
                                   join(t, ' ', format_name(order), ": vertex ", i, " is ",
                                        show(m.positions[i]), ", expected ", show(expected)));
            }
            CHECK(m.triangles.empty());
            CHECK(m.normals.empty());
        }
    }
}

TEST(every_integer_type_for_list_count_and_index) {
    for (const char* count_type : kIntegerTypes) {
        for (const char* index_type : kIntegerTypes) {
            for (const Order order : kOrders) {
                const std::string elements =
                    join("element vertex 4\n", kXyzFloat, "element face 2\nproperty list ",
                         count_type, ' ', index_type, " vertex_indices\n");
                std::vector<Record> records;
                for (int i = 0; i < 4; ++i)
                    records.push_back({{"float", i}, {"float", i * i}, {"float", 1}});
                const std::string c = count_type, x = index_type;
                records.push_back({{c, 4}, {x, 3}, {x, 2}, {x, 1}, {x, 0}});
                records.push_back({{c, 3}, {x, 1}, {x, 3}, {x, 0}});
                const MeshFile m = read_ply(ply(order, elements, records), "t.ply");
                const std::vector<Triangle> expected = {{3, 2, 1}, {3, 1, 0}, {1, 3, 0}};
                if (!same_triangles(m.triangles, expected))
                    record_failure(__FILE__, __LINE__,
                                   join(count_type, ' ', index_type, ' ', format_name(order),
                                        ": wrong triangles"));
            }
        }
    }
}

TEST(large_indices_in_wide_types) {
    // Index 70000 needs more than 16 bits; the file has 70001 vertices.
    for (const Order order : kOrders) {
        std::vector<Record> records;
        for (int i = 0; i <= 70000; ++i)
            records.push_back({{"uchar", i % 7}, {"uchar", i % 7}, {"uchar", i % 7}});
        records.push_back({{"uint8", 3}, {"uint32", 70000}, {"uint32", 65536}, {"uint32", 0}});
        const std::string elements =
            "element vertex 70001\nproperty uchar x\nproperty uchar y\nproperty uchar z\n"
            "element face 1\nproperty list uint8 uint32 vertex_indices\n";
        const MeshFile m = read_ply(ply(order, elements, records), "t.ply");
        CHECK_EQ(m.positions.size(), 70001u);
        CHECK(m.positions[70000] == (Vec3{70000 % 7, 70000 % 7, 70000 % 7}));
        CHECK(same_triangles(m.triangles, {{70000, 65536, 0}}));
    }
}

TEST(polygons_are_fans_from_their_first_vertex) {
    for (const Order order : kOrders) {
        std::vector<Record> records;
        for (int i = 0; i < 6; ++i) records.push_back({{"float", i}, {"float", 0}, {"float", 0}});
        records.push_back({{"uchar", 4}, {"int", 0}, {"int", 1}, {"int", 2}, {"int", 3}});
        records.push_back(
            {{"uchar", 6}, {"int", 5}, {"int", 4}, {"int", 3}, {"int", 2}, {"int", 1}, {"int", 0}});
        const std::string elements =
            join("element vertex 6\n", kXyzFloat,
                 "element face 2\nproperty list uchar int vertex_indices\n");
        const MeshFile m = read_ply(ply(order, elements, records), "t.ply");
        CHECK(same_triangles(m.triangles,
                             {{0, 1, 2}, {0, 2, 3}, {5, 4, 3}, {5, 3, 2}, {5, 2, 1}, {5, 1, 0}}));
    }
}

TEST(faces_of_fewer_than_three_vertices_are_skipped_and_noted) {
    for (const Order order : kOrders) {
        std::vector<Record> records = {{{"float", 0}, {"float", 0}, {"float", 0}},
                                       {{"float", 1}, {"float", 0}, {"float", 0}},
                                       {{"float", 0}, {"float", 1}, {"float", 0}},
                                       {{"uchar", 0}},
                                       {{"uchar", 1}, {"int", 2}},
                                       {{"uchar", 2}, {"int", 2}, {"int", 1}},
                                       {{"uchar", 3}, {"int", 2}, {"int", 1}, {"int", 0}}};
        const std::string elements =
            join("element vertex 3\n", kXyzFloat,
                 "element face 4\nproperty list uchar int vertex_indices\n");
        const MeshFile m = read_ply(ply(order, elements, records), "t.ply");
        CHECK(same_triangles(m.triangles, {{2, 1, 0}}));
        CHECK_EQ(m.notes.size(), 1u);
        if (!m.notes.empty())
            CHECK_EQ(m.notes[0], "PLY faces of fewer than 3 vertices skipped (3)");
    }
}

TEST(repeated_indices_are_kept) {
    for (const Order order : kOrders) {
        std::vector<Record> records = one_triangle();
        records.back() = {{"uchar", 3}, {"int", 1}, {"int", 1}, {"int", 2}};
        const MeshFile m = read_ply(ply(order, kOneTriangleElements, records), "t.ply");
        CHECK(same_triangles(m.triangles, {{1, 1, 2}}));
    }
}

TEST(other_properties_and_elements_are_skipped_whatever_their_type) {
    // z y x in another order, among scalars and lists of every kind; other elements before,
    // between and after; both normals; vertex_index as the list's name.
    const std::string elements =
        "element material 2\nproperty uchar red\nproperty list uint double weights\n"
        "element vertex 2\nproperty double confidence\nproperty float z\n"
        "property list ushort char tags\nproperty short y\nproperty float nz\n"
        "property int8 x\nproperty double ny\nproperty float nx\nproperty uint16 flags\n"
        "element edge 1\nproperty int vertex1\nproperty int vertex2\n"
        "element face 1\nproperty list int16 float texcoord\nproperty uchar hole\n"
        "property list uint8 uint16 vertex_index\nproperty list uchar int vertex_indices\n"
        "element camera 1\nproperty float64 view\n";
    std::vector<Record> records = {
        {{"uchar", 9}, {"uint", 2}, {"double", 0.25}, {"double", -1e300}},
        {{"uchar", 8}, {"uint", 0}},
        {{"double", 0.5},
         {"float", 3.5},
         {"ushort", 3},
         {"char", -1},
         {"char", 2},
         {"char", 3},
         {"short", -2},
         {"float", 0.125},
         {"int8", 1},
         {"double", 0.1},
         {"float", -0.25},
         {"uint16", 65535}},
        {{"double", 0.5},
         {"float", -3.5},
         {"ushort", 0},
         {"short", 2},
         {"float", 1},
         {"int8", -1},
         {"double", 0},
         {"float", 0},
         {"uint16", 0}},
        {{"int", 0}, {"int", 1}},
        {{"int16", 2},
         {"float", 0.5},
         {"float", 0.75},
         {"uchar", 1},
         {"uint8", 3},
         {"uint16", 1},
         {"uint16", 0},
         {"uint16", 1},
         {"uchar", 3},
         {"int", 0},
         {"int", 0},
         {"int", 0}},
        {{"float64", 2}}};
    MeshFile first;
    for (const Order order : kOrders) {
        const MeshFile m = read_ply(ply(order, elements, records), "t.ply");
        CHECK_EQ(m.positions.size(), 2u);
        CHECK_EQ(m.normals.size(), 2u);
        if (m.positions.size() != 2 || m.normals.size() != 2) continue;
        CHECK(m.positions[0] == (Vec3{1, -2, 3.5}));
        CHECK(m.positions[1] == (Vec3{-1, 2, -3.5}));
        CHECK(m.normals[0] == (Vec3{-0.25, 0.1, 0.125}));
        CHECK(m.normals[1] == (Vec3{0, 0, 1}));
        // The first list named as an index list is used.
        CHECK(same_triangles(m.triangles, {{1, 0, 1}}));
        const std::vector<std::string> notes = {
            "PLY element 'material' ignored",     "PLY vertex property 'confidence' ignored",
            "PLY vertex property 'tags' ignored", "PLY vertex property 'flags' ignored",
            "PLY element 'edge' ignored",         "PLY face property 'texcoord' ignored",
            "PLY face property 'hole' ignored",   "PLY face property 'vertex_indices' ignored",
            "PLY element 'camera' ignored",
        };
        CHECK(m.notes == notes);
        if (order == Order::kAscii) {
            first = m;
        } else {
            CHECK(m.positions == first.positions);
            CHECK(m.normals == first.normals);
            CHECK(m.triangles == first.triangles);
        }
    }
}

TEST(normals_need_all_three_components) {
    for (const Order order : kOrders) {
        const std::string elements =
            "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
            "property float nx\nproperty float ny\n";
        const MeshFile m =
            read_ply(ply(order, elements,
                         {{{"float", 1}, {"float", 2}, {"float", 3}, {"float", 4}, {"float", 5}}}),
                     "t.ply");
        CHECK(m.positions == (std::vector<Vec3>{{1, 2, 3}}));
        CHECK(m.normals.empty());
        CHECK(m.notes == (std::vector<std::string>{"PLY vertex property 'nx' ignored",
                                                   "PLY vertex property 'ny' ignored"}));
    }
}

TEST(comments_obj_info_blanks_tabs_and_line_ends_in_the_header) {
    const std::string lines[] = {"ply",
                                 "comment made by hand\t with tabs",
                                 "format \t  ascii\t1.0  ",
                                 "comment",
                                 "obj_info scanned 1994",
                                 "",
                                 "  element\t\tvertex   3",
                                 "property float x",
                                 "property\tfloat\ty",
                                 "property float  z\t",
                                 "element face 1",
                                 "property   list uchar int vertex_indices",
                                 "obj_info twice",
                                 "end_header"};
    for (const std::string eol : {"\n", "\r\n", "\r"}) {
        std::string text;
        for (const std::string& line : lines) text += line + eol;
        text += "0 0 0" + eol + "1\t0 0" + eol + "0 1 0  " + eol + eol + "3 0 1 2" + eol;
        const MeshFile m = read_ply(text, "t.ply");
        CHECK(m.positions == (std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
        CHECK(same_triangles(m.triangles, {{0, 1, 2}}));
        CHECK(m.notes == std::vector<std::string>{"PLY obj_info lines ignored"});
        CHECK(read_mesh_file(text, "t.ply").positions.size() == 3);
    }
}

TEST(binary_bodies_after_every_line_end) {
    // A body whose first byte is an LF (a float whose lowest byte is 10) after a header of
    // CR line ends: the body starts right after the CR.
    const float x = std::bit_cast<float>(0x3f80000aU);
    std::string records;
    put(records, x, false);
    put(records, 2.0f, false);
    put(records, 3.0f, false);
    for (const std::string eol : {"\n", "\r\n", "\r"}) {
        const std::string text = "ply" + eol + "format binary_little_endian 1.0" + eol +
                                 "element vertex 1" + eol + "property float x" + eol +
                                 "property float y" + eol + "property float z" + eol +
                                 "end_header" + eol + records;
        const MeshFile m = read_mesh_file(text, "t.ply");
        CHECK(m.positions == (std::vector<Vec3>{{x, 2, 3}}));
        CHECK(m.notes.empty());
    }
}

TEST(faces_may_come_before_vertices) {
    for (const Order order : kOrders) {
        std::vector<Record> records = one_triangle();
        std::rotate(records.begin(), records.begin() + 3, records.end());
        const std::string elements = kFaceList + "element vertex 3\n" + kXyzFloat;
        const MeshFile m = read_ply(ply(order, elements, records), "t.ply");
        CHECK(same_triangles(m.triangles, {{0, 1, 2}}));
        CHECK_EQ(m.positions.size(), 3u);
    }
}

TEST(elements_without_properties_take_no_time) {
    for (const Order order : kOrders) {
        const std::string elements =
            "element nothing 18446744073709551615\n" + kOneTriangleElements;
        const MeshFile m = read_ply(ply(order, elements, one_triangle()), "t.ply");
        CHECK_EQ(m.triangles.size(), 1u);
    }
}

TEST(trailing_bytes_are_noted) {
    MeshFile m =
        read_ply(ply(Order::kLittle, kOneTriangleElements, one_triangle()) + "xyz", "t.ply");
    CHECK(m.notes == std::vector<std::string>{"PLY bytes after the last element ignored (3)"});
    m = read_ply(ply(Order::kAscii, kOneTriangleElements, one_triangle()) + "\n \n", "t.ply");
    CHECK(m.notes.empty());
    m = read_ply(ply(Order::kAscii, kOneTriangleElements, one_triangle()) + "7\n", "t.ply");
    CHECK(m.notes == std::vector<std::string>{"PLY text after the last element ignored"});
}

TEST(content_tells_ply_from_obj) {
    CHECK(is_ply("ply\n"));
    CHECK(is_ply("ply\r\n"));
    CHECK(is_ply("ply\r"));
    CHECK(!is_ply("ply"));
    CHECK(!is_ply("plyx\n"));
    CHECK(!is_ply("v 0 0 0\n"));
    CHECK_ERROR(read_mesh_file("ply \nformat ascii 1.0\n", "m"),
                "m:1:1: expected an OBJ statement (v, vn, vt, f, o, g, s, usemtl, mtllib, l, p, "
                "...), found 'ply'");
}

TEST(header_errors_name_line_and_column) {
    CHECK_ERROR(read_ply("plx\nformat ascii 1.0\n", "t.ply"),
                "t.ply:1:1: expected the line 'ply', found 'plx'");
    CHECK_ERROR(read_ply("ply\nformat ascii 1.0\nelement vertex 0\n", "t.ply"),
                "t.ply:4:1: expected 'end_header', found the end of the file");
    CHECK_ERROR(read_ply("ply\r\nformat ascii 1.0\r\ncomment no end", "t.ply"),
                "t.ply:3:15: expected 'end_header', found the end of the file");
    CHECK_ERROR(read_ply("ply\nformat ebcdic 1.0\n", "t.ply"),
                "t.ply:2:8: expected ascii, binary_little_endian or binary_big_endian, found "
                "'ebcdic'");
    CHECK_ERROR(read_ply("ply\nformat ascii 2.0\n", "t.ply"),
                "t.ply:2:14: expected the version 1.0, found '2.0'");
    CHECK_ERROR(read_ply("ply\nformat ascii\n", "t.ply"),
                "t.ply:2:13: expected a format and the version 1.0, found the end of the line");
    CHECK_ERROR(read_ply("ply\nformat ascii 1.0\nformat ascii 1.0\n", "t.ply"),
                "t.ply:3:1: expected one format line, found a second");
    CHECK_ERROR(read_ply("ply\nelement vertex 0\nend_header\n", "t.ply"),
                "t.ply:3:1: expected a format line before end_header");
    CHECK_ERROR(read_ply("ply\nformat ascii 1.0\nelemnt vertex 3\n", "t.ply"),
                "t.ply:3:1: expected a header line (format, element, property, comment, obj_info "
                "or end_header), found 'elemnt'");
    CHECK_ERROR(read_ply("ply\nformat ascii 1.0\nproperty float x\n", "t.ply"),
                "t.ply:3:1: expected an element line before the first property");
    CHECK_ERROR(read_ply("ply\nformat ascii 1.0\nelement vertex -3\n", "t.ply"),
                "t.ply:3:16: expected a count (a whole number), found '-3'");
    CHECK_ERROR(read_ply("ply\nformat ascii 1.0\nelement vertex 99999999999999999999\n", "t.ply"),
                "t.ply:3:16: expected a count (a whole number), found '99999999999999999999'");
    CHECK_ERROR(read_ply("ply\nformat ascii 1.0\nelement vertex 3 4\n", "t.ply"),
                "t.ply:3:18: expected the end of the line, found '4'");
    CHECK_ERROR(read_ply("ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\n", "t.ply"),
                "t.ply:4:10: expected a type (char, uchar, short, ushort, int, uint, float, "
                "double, or int8 ... float64), found 'real'");
    CHECK_ERROR(
        read_ply("ply\nformat ascii 1.0\nelement f 1\nproperty list float int v\n", "t.ply"),
        "t.ply:4:15: expected an integer count type, found 'float'");
    CHECK_ERROR(read_ply("ply\nformat ascii 1.0\nelement v 1\nproperty list uchar int\n", "t.ply"),
                "t.ply:4:24: expected a count type, a value type and a name, found the end of "
                "the line");
    CHECK_ERROR(read_ply("ply\nformat ascii 1.0\nelement v 1\nproperty int a b\n", "t.ply"),
                "t.ply:4:16: expected the end of the line, found 'b'");
    CHECK_ERROR(
        read_ply("ply\nformat ascii 1.0\nelement v 1\nproperty int a\nproperty float a\n", "t.ply"),
        "t.ply:5:16: expected a new property name in element 'v', found 'a' a second "
        "time");
    CHECK_ERROR(
        read_ply("ply\nformat ascii 1.0\nelement vertex 0\n" + kXyzFloat + "element vertex 0\n",
                 "t.ply"),
        "t.ply:7:9: expected one element 'vertex', found a second");
    CHECK_ERROR(read_ply("ply\nformat ascii 1.0\nend_header now\n", "t.ply"),
                "t.ply:3:12: expected the end of the line, found 'now'");
}

TEST(header_errors_about_the_mesh_elements) {
    CHECK_ERROR(
        read_ply(header(Order::kAscii, "element vertex 1\nproperty float x\nproperty float z\n"),
                 "t.ply"),
        "t.ply:3:1: expected element 'vertex' to have a property 'y', found none");
    CHECK_ERROR(read_ply(header(Order::kAscii,
                                "element vertex 1\nproperty list uchar float x\n"
                                "property float y\nproperty float z\n"),
                         "t.ply"),
                "t.ply:4:1: expected vertex property 'x' to be a scalar, found a list");
    CHECK_ERROR(read_ply(header(Order::kAscii, "element face 1\nproperty list uchar int vertex\n"),
                         "t.ply"),
                "t.ply:3:1: expected element 'face' to have a list 'vertex_indices' (or "
                "'vertex_index'), found none");
    CHECK_ERROR(
        read_ply(header(Order::kAscii, "element face 1\nproperty int vertex_indices\n"), "t.ply"),
        "t.ply:4:1: expected face property 'vertex_indices' to be a list, found a scalar");
    CHECK_ERROR(
        read_ply(header(Order::kAscii, "element face 1\nproperty list uchar float vertex_index\n"),
                 "t.ply"),
        "t.ply:4:1: expected an integer type for the vertex indices, found 'float'");
    // A binary header's last line must end as its first does.
    CHECK_ERROR(read_ply("ply\r\nformat binary_little_endian 1.0\r\nend_header\n", "t.ply"),
                "t.ply:3:11: expected end_header's line to end as the 'ply' line does (the binary "
                "body may start with any byte), found another line end");
}

TEST(counts_the_file_cannot_hold_are_refused_before_reading) {
    // 2^31 vertices: more than indices can name.
    CHECK_ERROR(
        read_ply(header(Order::kLittle, "element vertex 2147483648\n" + kXyzFloat), "t.ply"),
        "t.ply:3:16: expected at most 2147483647 records in element 'vertex', found "
        "2147483648");
    CHECK_ERROR(read_ply(header(Order::kLittle, "element face 4294967296\n" + kFaceList), "t.ply"),
                "t.ply:3:14: expected at most 2147483647 records in element 'face', found "
                "4294967296");
    // 2^31 - 1 vertices of 12 bytes in a small file: refused at once, nothing reserved.
    const std::string claim = header(Order::kLittle, "element vertex 2147483647\n" + kXyzFloat);
    CHECK_ERROR(read_ply(claim + std::string(100, '\0'), "t.ply"),
                "t.ply:3:1: expected at most 8 records in element 'vertex' (each needs at least "
                "12 bytes, and 100 bytes follow the header), found 2147483647");
    CHECK_ERROR(
        read_ply(header(Order::kAscii, "element vertex 2147483647\n" + kXyzFloat) + "1 2 3\n",
                 "t.ply"),
        "t.ply:3:1: expected at most 1 records in element 'vertex' (each needs at least "
        "6 bytes, and 6 bytes follow the header), found 2147483647");
    // Counts add up over elements: the face element's records need bytes the vertices took.
    const std::string text = ply(Order::kLittle,
                                 "element vertex 3\n" + kXyzFloat +
                                     "element face 2\nproperty list uchar int vertex_indices\n",
                                 {one_triangle()[0], one_triangle()[1], one_triangle()[2]});
    CHECK_ERROR(read_ply(text, "t.ply"),
                "t.ply:7:1: expected at most 0 records in element 'face' (each needs at least 1 "
                "bytes, and 36 bytes follow the header), found 2");
    // An ignored element's absurd count is refused the same way.
    CHECK_ERROR(read_ply(header(Order::kBig,
                                "element junk 18446744073709551615\n"
                                "property double a\n") +
                             "12345678",
                         "t.ply"),
                "t.ply:3:1: expected at most 1 records in element 'junk' (each needs at least 8 "
                "bytes, and 8 bytes follow the header), found 18446744073709551615");
}

TEST(binary_body_errors_name_element_index_and_byte) {
    const std::string h = header(Order::kLittle, kOneTriangleElements);
    const std::size_t at = h.size();
    std::vector<Record> records = one_triangle();
    // Index out of range, negative, and an absurd list count.
    records[3] = {{"uchar", 3}, {"int", 0}, {"int", 3}, {"int", 2}};
    CHECK_ERROR(read_ply(h + body(Order::kLittle, records), "t.ply"),
                join("t.ply: face 0, byte ", at + 36 + 5,
                     ": expected a vertex index from 0 to 2, found 3"));
    records[3] = {{"uchar", 3}, {"int", 0}, {"int", 1}, {"int", -1}};
    CHECK_ERROR(read_ply(h + body(Order::kLittle, records), "t.ply"),
                join("t.ply: face 0, byte ", at + 36 + 9,
                     ": expected a vertex index from 0 to 2, found -1"));
    const std::string wide =
        header(Order::kBig, "element vertex 3\n" + kXyzFloat +
                                "element face 1\nproperty list uint uint vertex_indices\n");
    records[3] = {{"uint", 4294967295.0}, {"uint", 0}, {"uint", 1}, {"uint", 2}};
    CHECK_ERROR(read_ply(wide + body(Order::kBig, records), "t.ply"),
                join("t.ply: face 0, byte ", wide.size() + 36,
                     ": expected 17179869180 bytes for the 4294967295 values of list "
                     "'vertex_indices', found 12"));
    records[3] = {{"uint", 3}, {"uint", 0}, {"uint", 4294967295.0}, {"uint", 2}};
    CHECK_ERROR(read_ply(wide + body(Order::kBig, records), "t.ply"),
                join("t.ply: face 0, byte ", wide.size() + 36 + 8,
                     ": expected a vertex index from 0 to 2, found 4294967295"));
    const std::string signed_count =
        header(Order::kLittle, "element vertex 3\n" + kXyzFloat +
                                   "element face 1\nproperty list int int vertex_indices\n");
    records[3] = {{"int", -1}, {"int", 0}, {"int", 1}, {"int", 2}};
    CHECK_ERROR(read_ply(signed_count + body(Order::kLittle, records), "t.ply"),
                join("t.ply: face 0, byte ", signed_count.size() + 36,
                     ": expected a list count, found -1"));
    // Truncated inside a list.
    records = one_triangle();
    std::string cut = h + body(Order::kLittle, records);
    cut.resize(cut.size() - 2);
    CHECK_ERROR(read_ply(cut, "t.ply"),
                join("t.ply: face 0, byte ", at + 36,
                     ": expected 12 bytes for the 3 values of list 'vertex_indices', found 10"));
    // A skipped scalar cut short in an element of lists.
    const std::string skipped =
        header(Order::kLittle, "element extra 1\nproperty list uchar uchar a\nproperty double b\n");
    CHECK_ERROR(read_ply(skipped + "\x02\x01\x01" + "1234567", "t.ply"),
                join("t.ply: extra 0, byte ", skipped.size() + 3,
                     ": expected 8 bytes of property 'b' (double), found 7 before the end of the "
                     "file"));
}

TEST(binary_coordinates_must_be_finite) {
    const std::string h = header(Order::kBig, kOneTriangleElements);
    for (const float bad :
         {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
          -std::numeric_limits<float>::infinity()}) {
        std::vector<Record> records = one_triangle();
        records[1][1].value = bad;
        const std::string what = std::isnan(bad) ? "NaN" : bad > 0 ? "infinity" : "-infinity";
        CHECK_ERROR(read_ply(h + body(Order::kBig, records), "t.ply"),
                    join("t.ply: vertex 1, byte ", h.size() + 16,
                         ": expected a finite value of property 'y', found ", what));
    }
    // Normals too.
    const std::string hn = header(Order::kLittle, "element vertex 1\n" + kXyzFloat +
                                                      "property double nx\nproperty double ny\n"
                                                      "property double nz\n");
    const std::vector<Record> records = {{{"float", 0},
                                          {"float", 0},
                                          {"float", 0},
                                          {"double", 0},
                                          {"double", std::numeric_limits<double>::infinity()},
                                          {"double", 0}}};
    CHECK_ERROR(read_ply(hn + body(Order::kLittle, records), "t.ply"),
                join("t.ply: vertex 0, byte ", hn.size() + 20,
                     ": expected a finite value of property 'ny', found infinity"));
}

TEST(ascii_body_errors_name_line_column_element_and_index) {
    const std::string h = header(Order::kAscii, kOneTriangleElements);  // 9 lines
    const auto with = [&](const std::string& rest) { return h + rest; };
    CHECK_ERROR(read_ply(with("0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"), "t.ply"),
                "t.ply:13:7: face 0: expected a vertex index from 0 to 2, found 3");
    CHECK_ERROR(read_ply(with("0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"), "t.ply"),
                "t.ply:13:5: face 0: expected a vertex index from 0 to 2, found -1");
    CHECK_ERROR(read_ply(with("0 0 0\n1 0 0\n0 1 0\n3 0 1 4294967296\n"), "t.ply"),
                "t.ply:13:7: face 0: expected an integer from -2147483648 to 2147483647 for "
                "property 'vertex_indices', found '4294967296'");
    CHECK_ERROR(read_ply(with("0 0 0\n1 0 0\n0 1 0\n256 0 1 2\n"), "t.ply"),
                "t.ply:13:1: face 0: expected an integer from 0 to 255 for property "
                "'vertex_indices', found '256'");
    CHECK_ERROR(read_ply(with("0 0 0\n1 0 0\n0 1 0\n3.0 0 1 2\n"), "t.ply"),
                "t.ply:13:1: face 0: expected an integer from 0 to 255 for property "
                "'vertex_indices', found '3.0'");
    CHECK_ERROR(read_ply(with("0 0 0\n1 0 0\n0 1 0\n+-3 0 1 2\n"), "t.ply"),
                "t.ply:13:1: face 0: expected an integer from 0 to 255 for property "
                "'vertex_indices', found '+-3'");
    CHECK_ERROR(read_ply(with("0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"), "t.ply"),
                "t.ply:11:3: vertex 1: expected a finite number for property 'y', found 'nan'");
    CHECK_ERROR(read_ply(with("0 0 0\n1 0 -inf\n0 1 0\n3 0 1 2\n"), "t.ply"),
                "t.ply:11:5: vertex 1: expected a finite number for property 'z', found '-inf'");
    CHECK_ERROR(read_ply(with("0 0 0\n1 0 1e999\n0 1 0\n3 0 1 2\n"), "t.ply"),
                "t.ply:11:5: vertex 1: expected a finite number for property 'z', found '1e999'");
    CHECK_ERROR(read_ply(with("0 0 0\n1 0x 0\n0 1 0\n3 0 1 2\n"), "t.ply"),
                "t.ply:11:3: vertex 1: expected a finite number for property 'y', found '0x'");
    CHECK_ERROR(read_ply(with("0 0 0\n1 0 0\n0 1 0\n3 0 1    "), "t.ply"),
                "t.ply:13:10: face 0: expected a value of property 'vertex_indices' (int), found "
                "the end of the file");
    CHECK_ERROR(read_ply(with("0 0 0\n1 0 0\n0 1 0\n200 0 1 2 3 4 5\n"), "t.ply"),
                "t.ply:13:1: face 0: expected at most 7 values in list 'vertex_indices' (13 "
                "bytes are left), found 200");
    CHECK_ERROR(read_ply(with("0 0 0\n1 0 0\n0 1 0\n3 0 1"), "t.ply"),
                "t.ply:13:1: face 0: expected at most 2 values in list 'vertex_indices' (4 bytes "
                "are left), found 3");
    // A '+' is accepted, as in OBJ files, and ASCII keeps the decimal as written.
    const MeshFile m = read_ply(with("+0.1 0 0\n1 +2 0\n0 1 0\n+3 +0 +1 +2\n"), "t.ply");
    CHECK(m.positions[0] == (Vec3{0.1, 0, 0}));
    CHECK(m.positions[1] == (Vec3{1, 2, 0}));
    CHECK(same_triangles(m.triangles, {{0, 1, 2}}));
}

TEST(hostile_messages_quote_bytes_safely) {
    CHECK_ERROR(read_ply("ply\nformat ascii 1.0\n\x1b[31m\n", "t.ply"),
                "t.ply:3:1: expected a header line (format, element, property, comment, obj_info "
                "or end_header), found '\\x1b[31m'");
    CHECK_ERROR(read_ply("ply\nformat ascii 1.0\n" + std::string(100, 'a') + "\n", "t.ply"),
                "t.ply:3:1: expected a header line (format, element, property, comment, obj_info "
                "or end_header), found '" +
                    std::string(40, 'a') + "...'");
}

// Angle-weighted normals: closed forms.
TEST(angle_weighted_normals_of_an_octahedron_point_outwards) {
    const std::vector<Vec3> p = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                 {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    std::vector<Triangle> t;
    for (std::uint32_t x : {0u, 1u})
        for (std::uint32_t y : {2u, 3u})
            for (std::uint32_t z : {4u, 5u}) {
                // Counter-clockwise seen from outside: flip when the octant's sign count is odd.
                const bool odd = ((x == 1) != (y == 3)) != (z == 5);
                t.push_back(odd ? Triangle{x, z, y} : Triangle{x, y, z});
            }
    const std::vector<Vec3> n = angle_weighted_normals(p, t);
    CHECK_EQ(n.size(), 6u);
    for (std::size_t i = 0; i < n.size(); ++i) CHECK_NEAR(n[i], p[i], 1e-15);
}

TEST(angle_weighted_normals_weight_by_corner_angle) {
    // At the origin: a right angle in the plane z = 0 (normal +z) and 45 degrees in the plane
    // x = 0 (normal +x): the normal is (pi/4, 0, pi/2) normalised, that is (1, 0, 2) / sqrt 5.
    const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 1, 1}, {5, 5, 5}};
    const std::vector<Triangle> t = {{0, 1, 2}, {0, 2, 3}, {1, 1, 2}, {0, 1, 4}};
    std::vector<Triangle> with_degenerate = t;
    with_degenerate.pop_back();
    // The last triangle is replaced by a zero-area one (its vertices on a line).
    const std::vector<Vec3> q = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 1, 1}, {2, 0, 0}};
    with_degenerate.push_back({0, 1, 4});
    const std::vector<Vec3> n = angle_weighted_normals(q, with_degenerate);
    CHECK_NEAR(n[0], (Vec3{1, 0, 2}) / std::sqrt(5.0), 1e-15);
    CHECK_NEAR(n[1], (Vec3{0, 0, 1}), 1e-15);
    CHECK_NEAR(n[3], (Vec3{1, 0, 0}), 1e-15);
    // Vertex 4 has only the zero-area triangle: no normal, the zero vector.
    CHECK(n[4] == (Vec3{0, 0, 0}));
    // An isolated vertex too.
    CHECK(angle_weighted_normals(p, {})[4] == (Vec3{0, 0, 0}));
}
