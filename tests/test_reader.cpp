// The reader: lexical rules, structure, and every error of the contract with its place.
#include "error_cases.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {
const std::string kViewer = kTestViewer;
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
        CHECK(row.read && row.intersect && row.normal && row.bounds);
    }
}
