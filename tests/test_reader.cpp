// The reader: lexical rules, structure, and every error of the contract with its place.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "error_cases.h"
#include "rt/shape_arena.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {
const std::string kViewer = kTestViewer;

using Placements = std::vector<std::pair<std::uintptr_t, std::size_t>>;

// Places `bytes` in the arena, checks the alignment, writes its first and last byte, and
// notes where it went.
void place_and_touch(ShapeArena& arena, std::size_t bytes, std::size_t alignment,
                     Placements& placed) {
    auto* p = static_cast<unsigned char*>(arena.place(bytes, alignment));
    p[0] = p[bytes - 1] = 1;  // writable to its last byte
    CHECK_EQ(reinterpret_cast<std::uintptr_t>(p) % alignment, 0u);
    placed.emplace_back(reinterpret_cast<std::uintptr_t>(p), bytes);
}

bool none_overlap(Placements placed) {
    std::sort(placed.begin(), placed.end());
    for (std::size_t i = 1; i < placed.size(); ++i)
        if (placed[i - 1].first + placed[i - 1].second > placed[i].first) return false;
    return true;
}
}  // namespace

TEST(reads_the_original_example) {
    const Scene scene = parse_scene(
        "102\n0 2 3\n0 0 0\n1 0 0\n0 1 0\n256 256\n"
        "101\n-2 5 2\n1 1 1\n"
        "2\n0\n0 1 0\n100\n1 1 1\n0.0 30\n1.0 0 0\n");
    CHECK_EQ(scene.objects.size(), 1u);
    CHECK_EQ(scene.lights.size(), 1u);
    CHECK_EQ(scene.viewer.xres, 256);
    CHECK_NEAR(scene.viewer.eye, Vec3(0, 2, 3), 0);
    const Material m = scene.objects[0].surface->at({0, 0, 0});
    CHECK_EQ(m.ke, 30.0);
    CHECK_EQ(m.kd, 1.0);
    CHECK_EQ(m.ior, 0.0);  // the original's opaque example gives ior 0, which is accepted
}

TEST(comments_and_number_forms) {
    const Scene scene = parse_scene(
        "# a comment line\n102 0 0 5 # eye\n 0 0 0  1e0 0 0  0 1.0 0  4.0 2#res\n"
        "103 .5 0.25 2e-1\n103 0.5 0 0\n");
    CHECK_EQ(scene.viewer.xres, 4);
    CHECK_EQ(scene.viewer.yres, 2);
    CHECK_NEAR(scene.ambient, Spectrum(1.0, 0.25, 0.2), 1e-15);  // ambient lights add up
}

TEST(default_surface_is_shared) {
    const Scene scene =
        parse_scene(kViewer + "105 100 0.5 0.5 0.5 0 1 1 0 1\n" + "1 1 0 0 0 106\n1 1 3 0 0 106\n");
    CHECK_EQ(scene.objects.size(), 2u);
    CHECK(scene.objects[0].surface == scene.objects[1].surface);
    CHECK_NEAR(scene.objects[1].surface->at({}).colour, Spectrum(0.5), 0);
}

TEST(errors_name_line_column_and_expectation) {
    for (const ErrorCase& c : scene_error_cases()) CHECK_CONTAINS(scene_error(c.scene), c.message);
}

TEST(windows_line_endings_and_tabs) {
    const Scene scene = parse_scene("102\r\n0 0 5\t0 0 0\r\n1 0 0 0 1 0 3 3\r\n");
    CHECK_EQ(scene.viewer.xres, 3);
    CHECK_CONTAINS(scene_error("102\r\n0 0 5 0 0 0\r\n1 0 0 0 1 0 3 x\r\n"), "test.in:3:15:");
}

TEST(table_lookup) {
    CHECK(find_primitive_type(1) != nullptr);
    CHECK_EQ(std::string(find_primitive_type(2)->name), std::string("plane"));
    CHECK(find_primitive_type(0) == nullptr);
    CHECK(find_primitive_type(100) == nullptr);
    CHECK(find_surface_type(100) != nullptr);
    CHECK(find_light_type(101) != nullptr);
    CHECK(find_light_type(103) == nullptr);  // the ambient light is summed, not sampled
    for (const PrimitiveType& row : primitive_types()) {
        CHECK(row.id >= 1 && row.id <= 99);
        const PrimitiveFunctions& f = *row.functions;
        CHECK(f.read && f.intersect && f.normal && f.bounds);
    }
}

TEST(numbers_are_read_as_strtod_reads_them) {
    // The reader parses plain decimals itself and leaves the rest to strtod: the value must be
    // strtod's to the last bit, and what strtod refuses (or reads only in part) is refused.
    auto read_number = [](const std::string& text, double& value) {
        std::istringstream in(text);
        SceneReader reader(in, "test.in", {});
        try {
            value = reader.number("n");
        } catch (const Error&) {
            return false;
        }
        return true;
    };
    auto check = [&](const std::string& text) {
        char* end = nullptr;
        const double expected = std::strtod(text.c_str(), &end);
        const bool valid = end != text.c_str() && *end == '\0' && std::isfinite(expected);
        double value = 0;
        const bool read = read_number(text, value);
        CHECK_EQ(read, valid);
        if (read && valid && !(value == expected && std::signbit(value) == std::signbit(expected)))
            rt_test::record_failure(__FILE__, __LINE__, join(text, " read as ", value));
    };
    for (const char* text : {"1",
                             "-0.5",
                             "2e-3",
                             ".5",
                             "5.",
                             "-0",
                             "+0",
                             "+1.5",
                             "0x1p-2",
                             "-0X1.8P3",
                             "1e308",
                             "1.7976931348623157e308",
                             "1.7976931348623159e308",
                             "1e999",
                             "-1e999",
                             "1e-400",
                             "4.9e-324",
                             "2.4e-324",
                             "2.5e-324",
                             "1e-320",
                             "0.1000000000000000055511151231257827",
                             "9007199254740993",
                             "1E5",
                             "1e+5",
                             "00012",
                             "inf",
                             "-inf",
                             "nan",
                             "NAN",
                             "infinity",
                             "1e",
                             "1e+",
                             "--1",
                             "1.5.5",
                             ".",
                             "-",
                             "e5",
                             "0x",
                             "1,5",
                             "1f",
                             "0b1",
                             "12345678901"})
        check(text);
    Random random(123);
    for (int i = 0; i < 5000; ++i) {
        std::string text;
        const auto pick = random.next();
        if (pick % 4 == 1) text += '-';
        if (pick % 16 == 3) text += '+';
        const int digits = 1 + static_cast<int>(random.next() % 25);
        const int point = static_cast<int>(random.next() % (digits + 2)) - 1;
        for (int d = 0; d < digits; ++d) {
            if (d == point) text += '.';
            text += static_cast<char>('0' + random.next() % 10);
        }
        if (random.next() % 2 == 0) text += join('e', static_cast<int>(random.next() % 700) - 350);
        check(text);
    }
}

TEST(reading_in_chunks_keeps_every_place) {
    // Tokens, comments and line ends falling across the lexer's 64 KiB chunks, at every offset
    // near the boundary: the scene reads, and an error after it has its exact place.
    for (int pad = 0; pad < 40; ++pad) {
        std::string text = kViewer;
        int line = 2, lights = 0;
        while (text.size() < 65536 - 40 + static_cast<std::size_t>(pad)) {
            text += "103 0.125 0.25 0.5 # ambient\r\n";
            ++line;
            ++lights;
        }
        text += std::string(static_cast<std::size_t>(pad % 7), ' ');
        text += "103 1.0000000000000002 0.25 -0.5e-300\n";
        text += "# a comment across the boundary\n";
        line += 2;
        const Scene scene = parse_scene(text);
        CHECK_EQ(scene.ambient[0], 0.125 * lights + 1.0000000000000002);
        CHECK_CONTAINS(scene_error(text + "  x"),
                       join("test.in:", line, ":3: expected object ID (a number), got 'x'"));
        CHECK_CONTAINS(scene_error(text + "103 1 2"),
                       join("test.in:", line, ":8: unexpected end of file"));
        CHECK_CONTAINS(scene_error(text + " 103 1 " + std::string(5000, '2')),
                       join("test.in:", line, ":8: token longer than 4096 characters"));
    }
}

TEST(many_spheres_keep_their_parameters_in_the_arena_after_the_reader) {
    // 20,000 spheres fill several of the arena's blocks (16 KiB, doubling to 4 MiB); the
    // scene outlives its reader, and every sphere's bounds are its own.
    std::string text = kViewer + "105 100 0.5 0.5 0.5 0 1 1 0 1\n";
    for (int i = 0; i < 20000; ++i)
        text += "1 " + std::to_string(0.25 + i % 7) + " " + std::to_string(i) + " " +
                std::to_string(-i) + " 3 106\n";
    // Planes and triangles between them: shapes of other sizes in the same blocks.
    text += "2 -5 0 1 0 106\n5 0 0 0 1 0 0 0 1 0 106\n";
    const Scene scene = parse_scene(text);
    CHECK_EQ(scene.objects.size(), 20002u);
    bool same = true;
    for (int i = 0; i < 20000; ++i) {
        const Bounds b = scene.objects[static_cast<std::size_t>(i)].shape.bounds();
        const double r = 0.25 + i % 7;
        same =
            same && b.min.x == i - r && b.max.x == i + r && b.min.y == -i - r && b.max.z == 3 + r;
    }
    CHECK(same);
    // A copy of the scene keeps the shapes alive after the first is gone.
    std::optional<Scene> first = scene;
    const Scene second = *first;
    first.reset();
    CHECK_EQ(second.objects[19999].shape.bounds().max.x, 19999 + 0.25 + 19999 % 7);
}

TEST(surfaces_and_polygons_keep_their_data_in_the_arena_after_the_reader) {
    // A surface of its own for every object (its colour its number), and polygons of 40
    // vertices (outline and edge bands placed after each polygon) between spheres; the scene
    // outlives its reader and the first copy of it.
    std::string text = kViewer;
    constexpr int kObjects = 3000;
    for (int i = 0; i < kObjects; ++i) {
        const std::string surface = " 100 " + std::to_string(i) + " 0.5 1  0 1 1 0 1\n";
        if (i % 2 == 0) {
            text += "1 0.5 " + std::to_string(3 * i) + " 0 0" + surface;
            continue;
        }
        // A regular 40-gon of radius 1 about (3i, 5, 0) in the plane z = 0.
        text += "11 40";
        for (int k = 0; k < 40; ++k) {
            const double a = 2 * M_PI * k / 40;
            text += " " + std::to_string(3 * i + std::cos(a)) + " " +
                    std::to_string(5 + std::sin(a)) + " 0";
        }
        text += surface;
    }
    std::optional<Scene> first = parse_scene(text);
    const Scene scene = *first;
    first.reset();
    CHECK_EQ(scene.objects.size(), static_cast<std::size_t>(kObjects));
    bool colours = true, hits = true, misses = true;
    for (int i = 0; i < kObjects; ++i) {
        const Object& object = scene.objects[static_cast<std::size_t>(i)];
        const Material m = object.surface->at({});
        colours = colours && m.colour[0] == i && m.colour[1] == 0.5 && m.colour[2] == 1;
        if (i % 2 == 0) continue;
        // Straight down through the centre at 7, and just outside the outline (0.999 of the
        // way to a vertex lies inside, 1.001 outside).
        Hit hit;
        const double x = 3 * i;
        hits = hits && object.shape.intersect({{x + 0.3, 5.2, 7}, {0, 0, -1}}, {1e-9, 100}, hit) &&
               std::fabs(hit.t - 7) < 1e-12 &&
               object.shape.intersect({{x + 0.999, 5, 1}, {0, 0, -1}}, {1e-9, 100}, hit);
        misses = misses &&
                 !object.shape.intersect({{x + 1.001, 5, 1}, {0, 0, -1}}, {1e-9, 100}, hit) &&
                 !object.shape.intersect({{x, 6.01, 1}, {0, 0, -1}}, {1e-9, 100}, hit);
    }
    CHECK(colours);
    CHECK(hits);
    CHECK(misses);
}

TEST(the_arena_places_shapes_of_any_size_apart) {
    // Sizes around the blocks' (16 KiB doubling to 4 MiB) and beyond the size that has a
    // block of its own (1 MiB), between small ones: each writable to its last byte, none
    // overlapping another.
    ShapeArena arena;
    Placements placed;
    const std::size_t sizes[] = {24,
                                 16 << 10,
                                 40,
                                 (16 << 10) + 8,
                                 100000,
                                 8,
                                 ShapeArena::kOwnBlockFrom,
                                 64,
                                 ShapeArena::kOwnBlockFrom + 1,
                                 48,
                                 3 << 20,
                                 200,
                                 700000,
                                 16};
    for (int round = 0; round < 3; ++round)
        for (const std::size_t bytes : sizes) place_and_touch(arena, bytes, 8, placed);
    CHECK(none_overlap(placed));
}

TEST(the_arena_places_shapes_apart_and_aligned) {
    ShapeArena arena;
    Placements placed;
    for (int i = 0; i < 100000; ++i) {
        const std::size_t bytes = 8 + static_cast<std::size_t>(i * 37 % 249);
        const std::size_t alignment = std::size_t{8} << (i % 4);  // 8 to 64
        place_and_touch(arena, bytes, alignment, placed);
    }
    CHECK(none_overlap(placed));
}
