// The reader: lexical rules, structure, and every error of the contract with its place.
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {
const std::string kViewer = kTestViewer;
const std::string kSurface = " 100 1 1 1 0 1 1 0 1";
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
    const Scene scene = parse_scene(kViewer + "105 100 0.5 0.5 0.5 0 1 1 0 1\n" +
                                    "1 1 0 0 0 106\n1 1 3 0 0 106\n");
    CHECK_EQ(scene.objects.size(), 2u);
    CHECK(scene.objects[0].surface == scene.objects[1].surface);
    CHECK_NEAR(scene.objects[1].surface->at({}).colour, Spectrum(0.5), 0);
}

TEST(errors_name_line_column_and_expectation) {
    struct Case {
        std::string scene;
        std::string message;
    };
    const Case cases[] = {
        {kViewer + "42 1 2 3", "test.in:2:1: unknown object ID 42"},
        {kViewer + "1 1 0 0", "test.in:2:8: unexpected end of file: expected sphere centre"},
        {kViewer + "1 1 0 x 0" + kSurface, "test.in:2:7: expected sphere centre (a number), got 'x'"},
        {kViewer + "1 1 0 0 inf" + kSurface, "test.in:2:9: sphere centre must be a finite number, got 'inf'"},
        {kViewer + "1 1 0 0 nan" + kSurface, "sphere centre must be a finite number, got 'nan'"},
        {kViewer + "1 1 0 0 1e999" + kSurface, "sphere centre must be a finite number, got '1e999'"},
        {kViewer + "1.5 1 0 0 0" + kSurface, "test.in:2:1: object ID must be a whole number, got 1.5"},
        {kViewer + "100 1 1 1 0 1 1 0 1", "test.in:2:1: surface 100 (simple surface) found where an object is expected"},
        {kViewer + "106", "test.in:2:1: surface 106 (use default surface) found where an object is expected"},
        {"103 1 1 1", "test.in:1:10: no viewer (102) in the scene"},
        {"", "test.in:1:1: no viewer (102) in the scene"},
        {kViewer + kViewer, "test.in:2:1: a second viewer (102); a scene has exactly one"},
        {"102 0 0 5 0 0 0 1 0 0 0 1 0 0 4", "test.in:1:29: viewer x resolution must be between 1 and 16384, got 0"},
        {"102 0 0 5 0 0 0 1 0 0 0 1 0 4 -3", "test.in:1:31: viewer y resolution must be between 1 and 16384, got -3"},
        {"102 0 0 5 0 0 0 1 0 0 0 1 0 16385 4", "viewer x resolution must be between 1 and 16384, got 16385"},
        {"102 0 0 5 0 0 0 1 0 0 0 1 0 16384 16384", "test.in:1:29: viewer resolution 16384x16384 exceeds the limit of 67108864 pixels"},
        {"102 0 0 5 0 0 0 1 0 0 0 1 0 4.5 4", "viewer x resolution must be a whole number, got 4.5"},
        {"102 0 0 5 0 0 5 1 0 0 0 1 0 4 4", "test.in:1:11: viewer look-at point must differ from the eye position"},
        {"102 0 0 5 0 0 0 0 0 0 0 1 0 4 4", "test.in:1:17: viewer x vector must have a non-zero, finite length"},
        {kViewer + "2 0 0 0 0" + kSurface, "test.in:2:5: plane normal must have a non-zero, finite length"},
        {kViewer + "1 1 0 0 0 106", "test.in:2:11: 106 (use default surface) but no default surface has been set with 105"},
        {kViewer + "1 1 0 0 0 101 1 1 1 1 1 1", "test.in:2:11: expected a surface ID (one of 100, 106, 107, 108, 111), got 101 (point light)"},
        {kViewer + "1 1 0 0 0 100 1 1 -1 0 1 1 0 1", "test.in:2:15: surface colour components must be >= 0"},
        {kViewer + "1 1 0 0 0 100 1 1 1 0 1 1 0.5 0", "test.in:2:31: surface ior must be > 0 when kt > 0, got 0"},
        {kViewer + "1 1 0 0 0 100 1 1 1 -0.5 1 1 0 1", "test.in:2:21: surface ks (specular coefficient) must be >= 0, got -0.5"},
        {kViewer + "\"quoted\"", "test.in:2:1: expected object ID (a number), got a quoted string"},
        {kViewer + "\"unterminated", "test.in:2:1: unterminated quoted path"},
        {kViewer + std::string(5000, '1'), "test.in:2:1: token longer than 4096 characters"},
    };
    for (const Case& c : cases) CHECK_CONTAINS(scene_error(c.scene), c.message);
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
        CHECK(row.read && row.intersect && row.normal && row.bounds);
    }
}
