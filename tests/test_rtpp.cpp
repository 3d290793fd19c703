// rtpp, the readable scene language: expressions against hand-computed values, transforms
// against the frames they must write, the camera against the viewer it must write, errors
// with their places and include chains, line markers through rt, and the limits.
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "check.h"
#include "cli_util.h"
#include "memory_checks.h"  // RT_MEASURES_MEMORY: 0 under ASan
#include "rt/reader.h"
#include "rtpp/compiler.h"
#include "rtpp/kinds.h"
#include "rtpp/transform.h"
#include "rtpp_util.h"

namespace fs = std::filesystem;
using rt_test::litter;
using rt_test::read_file;
using rt_test::write_file;
using rtpp_test::error_of;
using rtpp_test::file_error_of;
using rtpp_test::kCamera;

namespace {

// The compiled scene without its header and markers.
std::string compile_body(const std::string& source) {
    const std::string out = rtpp::compile(source, "t.rts", ".");
    std::istringstream in(out);
    std::string line, body;
    while (std::getline(in, line))
        if (!line.empty() && line[0] != '#') body += line + "\n";
    return body;
}

// The last line written (after the camera): the object under test.
std::string last_line(const std::string& source) {
    const std::string body = compile_body(kCamera + source);
    const std::size_t end = body.size() - 1;
    return body.substr(body.rfind('\n', end - 1) + 1, end - body.rfind('\n', end - 1) - 1);
}

// The value an expression gives, written as an ambient light's intensity.
std::string value_of(const std::string& expression) {
    return last_line("ambient { intensity " + expression + " }");
}

}  // namespace

TEST(expressions_give_hand_computed_values) {
    CHECK_EQ(value_of("1 + 2 * 3"), std::string("103 7 7 7"));
    CHECK_EQ(value_of("(1 + 2) * 3"), std::string("103 9 9 9"));
    CHECK_EQ(value_of("-2 ^ 2"), std::string("103 -4 -4 -4"));
    CHECK_EQ(value_of("2 ^ 3 ^ 2"), std::string("103 512 512 512"));
    CHECK_EQ(value_of("7 / 2 - 1"), std::string("103 2.5 2.5 2.5"));
    CHECK_EQ(value_of("-1 % 3"), std::string("103 2 2 2"));
    CHECK_EQ(value_of("<sin(30), cos(60), tan(45)>"), std::string("103 0.5 0.5 1"));
    CHECK_EQ(value_of("<sin(90), cos(90), sin(180)>"), std::string("103 1 0 0"));
    CHECK_EQ(value_of("<sqrt(16), pow(2, 10), abs(-3)>"), std::string("103 4 1024 3"));
    CHECK_EQ(value_of("<min(3, 1, 2), max(3, 1, 2), round(2.675, 2)>"),
             std::string("103 1 3 2.67"));  // 2.675 is 2.67499999... as a double
    CHECK_EQ(value_of("<length(<3, 4, 0>), dot(<1, 2, 3>, <4, 5, 6>), 0>"),
             std::string("103 5 32 0"));
    CHECK_EQ(value_of("cross(x, y)"), std::string("103 0 0 1"));
    CHECK_EQ(value_of("normalize(<0, 0, 7>)"), std::string("103 0 0 1"));
    CHECK_EQ(value_of("<1, 2, 3> * 2 + <1, 1, 1> / 2"), std::string("103 2.5 4.5 6.5"));
    CHECK_EQ(value_of("<1, 2, 3>.y"), std::string("103 2 2 2"));
    CHECK_EQ(value_of("<(1 < 2), (2 <= 1), (1 == 1 and not (2 != 2))>"),
             std::string("103 1 0 1"));  // a comparison inside a vector is parenthesised
    CHECK_EQ(value_of("pi"), std::string("103 3.141592653589793 3.141592653589793 "
                                         "3.141592653589793"));
    CHECK_EQ(compile_body(kCamera + "let r = 2\nlet c = <1, r, 3>\n"
                                    "sphere { radius r * 2 centre c surface { colour 1 kd 1 } }")
                 .substr(compile_body(kCamera).size()),
             std::string("1 4 1 2 3 100 1 1 1 0 1 1 0 1\n"));
}

TEST(every_object_kind_writes_its_contract_numbers) {
    const std::string s = " surface { colour <0.1, 0.2, 0.3> ks 0.4 ke 5 kd 0.6 kt 0.7 ior 1.5 }";
    const std::string surface = "100 0.1 0.2 0.3 0.4 5 0.6 0.7 1.5";
    CHECK_EQ(last_line("plane { normal y distance 2" + s + " }"), "2 2 0 1 0 " + surface);
    CHECK_EQ(last_line("disk { centre <1, 2, 3> normal z radius 4" + s + " }"),
             "3 1 2 3 0 0 1 4 " + surface);
    CHECK_EQ(last_line("annulus { normal z outer 4 inner 1" + s + " }"),
             "4 0 0 0 0 0 1 4 1 " + surface);
    CHECK_EQ(last_line("triangle { vertex x vertex y vertex z" + s + " }"),
             "5 1 0 0 0 1 0 0 0 1 " + surface);
    CHECK_EQ(last_line("parallelogram { a x b y" + s + " }"), "6 0 0 0 1 0 0 0 1 0 " + surface);
    CHECK_EQ(last_line("cone { angle 60 axis y" + s + " }"), "8 0.5 0 1 0 0 0 0 1 0 " + surface);
    CHECK_EQ(last_line("cylinder { radius 1 axis y finish 3" + s + " }"),
             "9 1 0 3 0 0 0 0 1 0 " + surface);
    CHECK_EQ(last_line("torus { axis y major 2 minor 0.5" + s + " }"),
             "10 0 0 0 0 1 0 2 0.5 " + surface);
    CHECK_EQ(last_line("polygon { vertex x vertex y vertex z vertex -x" + s + " }"),
             "11 4 1 0 0 0 1 0 0 0 1 -1 0 0 " + surface);
    CHECK_EQ(last_line("box { min -x max y" + s + " }"), "12 -1 0 0 0 1 0 " + surface);
    CHECK_EQ(last_line("quadric { xx 1 yy 2 zz 3 xy 4 xz 5 yz 6 x 7 y 8 z 9 constant 10 "
                       "min -x max x" +
                       s + " }"),
             "13 1 2 3 4 5 6 7 8 9 10 -1 0 0 1 0 0 " + surface);
    CHECK_EQ(last_line("mesh { vertex x vertex y vertex z triangle <0, 1, 2>" + s + " }"),
             "14 3 1 1 0 0 0 1 0 0 0 1 0 1 2 " + surface);
    CHECK_EQ(last_line("sphere { radius 1 surface glass { ior 1.5 } }"),
             "1 1 0 0 0 114 1 1 1 0 1 0 1.5 0 0 0");
    CHECK_EQ(last_line("sphere { radius 1 surface checker { cell 2 a surface { colour 1 kd 1 } "
                       "b surface { colour 0 kd 1 } } }"),
             "1 1 0 0 0 107 2 100 1 1 1 0 1 1 0 1 100 0 0 0 0 1 1 0 1");
    CHECK_EQ(last_line("point_light { position y intensity 2 }"), "104 0 1 0 2 2 2");
    CHECK_EQ(last_line("point_light { position y intensity 2 falloff true }"), "101 0 1 0 2 2 2");
    CHECK_EQ(last_line("spot_light { position y direction -y cutoff_angle 60 intensity 1 }"),
             "109 0 1 0 0 -1 0 0.5 0 1 1 1");
    CHECK_EQ(last_line("sphere_light { radius 1 intensity 1 }"), "110 16 0 0 0 1 1 1 1");
    CHECK_EQ(last_line("directional_light { direction -y intensity 1 }"), "113 0 -1 0 1 1 1");
    // Unions nest to the right; a difference takes the union of the rest from the first.
    const std::string ball = "sphere { radius 1 surface { colour 1 kd 1 } }";
    CHECK_EQ(compile_body(kCamera + "difference {" + ball + ball + ball + "}")
                 .substr(compile_body(kCamera).size()),
             std::string("22 1 1 0 0 0 100 1 1 1 0 1 1 0 1 20 1 1 0 0 0 100 1 1 1 0 1 1 0 1 "
                         "1 1 0 0 0 100 1 1 1 0 1 1 0 1\n"));
    // A default surface, then primitives without one take it (106).
    CHECK_EQ(compile_body(kCamera + "default_surface surface { colour 1 kd 1 }\n"
                                    "sphere { radius 1 }")
                 .substr(compile_body(kCamera).size()),
             std::string("105 100 1 1 1 0 1 1 0 1\n1 1 0 0 0 106\n"));
}

TEST(every_kind_row_is_whole) {
    // The emitter writes a kind from its row alone, so a row must name what it writes with.
    for (const rtpp::Kind& kind : rtpp::all_kinds()) {
        std::vector<std::string> names, listed;
        for (const rtpp::FieldSpec& spec : kind.fields) {
            names.emplace_back(spec.name);
            if (spec.other == nullptr) continue;
            const rtpp::FieldSpec* other = kind.field(spec.other);
            CHECK(other != nullptr && other->write == rtpp::Write::none);
        }
        if (kind.category == rtpp::Category::primitive)
            CHECK(kind.fields.back().write == rtpp::Write::slot);
        if (kind.category == rtpp::Category::csg) CHECK(kind.rest_id != 0 && kind.fields.empty());
        // A kind listed in another order lists the same fields.
        std::istringstream in(kind.field_names());
        for (std::string name; std::getline(in >> std::ws, name, ',');) listed.push_back(name);
        std::sort(names.begin(), names.end());
        std::sort(listed.begin(), listed.end());
        CHECK(names == listed);
    }
}

TEST(transforms_write_the_frames_that_map_points_alike) {
    // Points mapped by the composed frame and by each transform in turn agree.
    const rtpp::Frame t =
        rtpp::compose(rtpp::translation({1, 2, 3}),
                      rtpp::compose(rtpp::rotation(90, {0, 1, 0}), rtpp::scaling({2, 2, 2})));
    const rt::Vec3 p{1, 0, 0};
    CHECK_NEAR(t.point(p), (rt::Vec3{1, 2, 1}), 1e-15);  // scaled to 2, turned to -z, moved
    CHECK_EQ(t.point(p).z, 1.0);                         // quarter turns are exact
    rt_test::Random random(7);
    for (int i = 0; i < 100; ++i) {
        const rt::Vec3 axis = random.unit_vector();
        const double angle = random.uniform(-360, 360);
        const rtpp::Frame r = rtpp::rotation(angle, axis);
        const rt::Vec3 q = random.in_box(3);
        // A rotation keeps lengths and the axis, and turns by the angle.
        CHECK_NEAR(rt::length(r.point(q)), rt::length(q), 1e-12);
        CHECK_NEAR(r.point(axis), axis, 1e-12);
    }
    // In the language: transforms apply in the order written.
    CHECK_EQ(last_line("sphere { radius 1 surface { colour 1 kd 1 } scale 2 rotate 90 about y "
                       "translate <1, 2, 3> }"),
             std::string("7 1 2 3 0 0 -2 0 2 0 2 0 0 1 1 0 0 0 100 1 1 1 0 1 1 0 1"));
    CHECK_EQ(last_line("point_light { position x intensity 1 translate y }"),
             std::string("112 0 1 0 1 0 0 0 1 0 0 0 1 104 1 0 0 1 1 1"));
    CHECK_EQ(last_line("sphere { radius 1 surface checker { cell 1 a surface { colour 1 kd 1 } "
                       "b surface { colour 0 kd 1 } scale 2 } }"),
             std::string("1 1 0 0 0 111 0 0 0 2 0 0 0 2 0 0 0 2 107 1 100 1 1 1 0 1 1 0 1 100 0 "
                         "0 0 0 1 1 0 1"));
    // A group's transform composes with each member's.
    CHECK_EQ(compile_body(kCamera + "group { sphere { radius 1 surface { colour 1 kd 1 } "
                                    "translate x } scale 2 }")
                 .substr(compile_body(kCamera).size()),
             std::string("7 2 0 0 2 0 0 0 2 0 0 0 2 1 1 0 0 0 100 1 1 1 0 1 1 0 1\n"));
}

TEST(the_camera_writes_square_pixel_viewer_vectors) {
    CHECK_EQ(compile_body(kCamera), std::string("102 0 0 5 0 0 0 1 0 0 0 1 0 4 4\n"));
    // 90 degrees across a 2:1 image: x is tan 45 = 1 wide, y half that, perpendicular.
    const std::string wide =
        compile_body("camera { position <0, 0, 5> look_at <0, 0, 0> fov 90 size 200, 100 }");
    CHECK_EQ(wide, std::string("102 0 0 5 0 0 0 1 0 0 0 0.5 0 200 100\n"));
    // Looking down: y tilts back, perpendicular to the view; upright keeps it vertical.
    const std::string down =
        compile_body("camera { position <0, 3, 3> look_at <0, 0, 0> half_width 1 size 10, 10 }");
    CHECK_EQ(down, std::string("102 0 3 3 0 0 0 1 0 0 0 0.7071067811865476 -0.7071067811865476 "
                               "10 10\n"));
    CHECK_EQ(compile_body("camera { position <0, 3, 3> look_at <0, 0, 0> half_width 1 size 10, "
                          "10 upright true }"),
             std::string("102 0 3 3 0 0 0 1 0 0 0 1 0 10 10\n"));
}

TEST(errors_name_their_place) {
    const std::pair<std::string, std::string> cases[] = {
        {"sphere { radius 1 surface { colour 1 kd 1 } }", "t.rts:1:46: no camera in the scene"},
        {kCamera + "sphere { centre x surface { colour 1 kd 1 } }",
         "t.rts:2:1: sphere: missing field 'radius'"},
        {kCamera + "sphere { radius 1 }",
         "t.rts:2:1: sphere: missing field 'surface' (and no default_surface is set)"},
        {kCamera + "sphere {\n  radus 1 }",
         "t.rts:3:3: a sphere has no field 'radus'; did you mean 'radius'? (it has: "
         "radius, centre, surface; translate, rotate, scale, "
         "frame)"},
        {kCamera + "sphere { radius <1, 2, 3> }",
         "t.rts:2:17: sphere radius must be a number, got a vector"},
        {kCamera + "sphre { }", "t.rts:2:1: unknown object kind 'sphre'"},
        {kCamera + "let a = 1 +", "t.rts:2:12: expected a value, got end of file"},
        {kCamera + "let a = (1 + 2", "t.rts:2:15: expected ')' to close the '(' at 2:9"},
        {kCamera + "let a = <1, 2>", "t.rts:2:14: expected ',' between a vector's components"},
        {kCamera + "let a = b", "t.rts:2:9: unknown name 'b'"},
        {kCamera + "let a = 1 / 0", "t.rts:2:11: division by zero"},
        {kCamera + "let a = 2x", "t.rts:2:9: a number may not run into a name"},
        {kCamera + "let a = \"abc", "t.rts:2:9: unterminated string"},
        {kCamera + "let a = 1 @", "t.rts:2:11: unexpected character '@'"},
        {kCamera + "let a = foo(1)", "t.rts:2:9: unknown function 'foo'"},
        {kCamera + "let a = sqrt(1, 2)", "t.rts:2:9: sqrt takes 1 argument, got 2"},
        {kCamera + "sphere { radius 1", "t.rts:2:18: end of file inside sphere begun at 2:1"},
        {kCamera + "for i = 0 to 3 step 0 { }", "t.rts:2:21: a loop's step must not be 0"},
        {kCamera + kCamera, "t.rts:2:1: a second camera; a scene has exactly one"},
        {kCamera + "surface { colour 1 kd 1 }", "t.rts:2:1: a surface surface on its own"},
        {kCamera + "sphere { radius 1 box { min x max y } }",
         "t.rts:2:19: a sphere cannot hold other objects"},
        {kCamera + "union { sphere { radius 1 surface { colour 1 kd 1 } } }",
         "t.rts:2:1: union needs at least two objects, got 1"},
        {kCamera + "cone { axis y surface { colour 1 kd 1 } }",
         "t.rts:2:1: cone: missing field 'alpha' (or 'angle')"},
        {kCamera + "mesh { vertex x triangle <0, 0, 1> surface { colour 1 kd 1 } }",
         "t.rts:2:17: mesh triangle indices must be whole numbers from 0 to 0"},
        {kCamera + "translate x", "t.rts:2:1: translate belongs inside an object's"},
        {kCamera + "let sphere = 1", "t.rts:2:1: 'sphere' is an object kind"},
        {kCamera + "let for = 1", "t.rts:2:1: 'for' is a reserved word"},
        {"camera { position x look_at x fov 90 size 4, 4 }",
         "t.rts:1:1: camera look_at must differ from its position"},
        {"camera { position x look_at y fov 180 size 4, 4 }",
         "t.rts:1:31: camera fov must be between 0 and 180 degrees"},
        {"camera { position x look_at y fov 90 size 4.5, 4 }",
         "t.rts:1:43: camera size must be whole numbers from 1 to 16384, got 4.5"},
    };
    for (const auto& [source, message] : cases) CHECK_CONTAINS(error_of(source), message);
}

// A field given twice in one object's braces is an error naming both places (one inherited
// from a named object is overridden, as always); mistyped names and fields get the nearest.
TEST(repeated_fields_and_near_misses) {
    CHECK_CONTAINS(error_of(kCamera + "torus { major 1 major 2 axis y minor 0.2 }"),
                   "t.rts:2:17: 'major' is given twice in this torus (first at t.rts:2:9); give "
                   "each field once");
    CHECK_EQ(error_of(kCamera + "let r = surface { colour 1 kd 1 }\n"
                                "sphere { radius 1 surface r { colour 0.5 } }"),
             "");
    CHECK_CONTAINS(error_of(kCamera + "let blue = surface { colour <0, 0, 1> kd 1 }\n"
                                      "sphere { radius 1 surface bleu }"),
                   "t.rts:3:27: unknown name 'bleu'; did you mean 'blue'?");
    CHECK_CONTAINS(error_of(kCamera + "sphere { radius 1 surface { colour 1 kd 1 } centr x }"),
                   "a sphere has no field 'centr'; did you mean 'centre'?");
    // Nothing near: no suggestion.
    const std::string far = error_of(kCamera + "sphere { radius 1 surface zzzzzz }");
    CHECK_CONTAINS(far, "unknown name 'zzzzzz'");
    CHECK(far.find("did you mean") == std::string::npos);
}

// A numeric scene given to rtpp is pointed to rt, as a readable one given to rt is to rtpp.
TEST(a_numeric_scene_given_to_rtpp_gets_a_note) {
    CHECK_EQ(error_of("102 0 0 5 0 0 0 1 0 0 0 1 0 8 6\n"),
             std::string("t.rts:1:1: expected a statement (a field, an object, let, for, if or "
                         "include), got '102'\nt.rts:1:1: note: this looks like rt's numeric "
                         "scene format, which rt reads as it is: rt SCENE -o IMAGE (rtpp compiles "
                         "the readable language)"));
    // Inside braces a number is only out of place.
    CHECK(error_of(kCamera + "group { 5 }").find("note:") == std::string::npos);
}

// -D NAME=VALUE: bound before the program, an expression of the language, and winning over
// the program's own top-level let of the name (its default).
TEST(defines_override_the_programs_defaults) {
    const std::string source = kCamera +
                               "let frame = 0\nsphere { radius 1 + frame / 10 centre <0, 0, -size> "
                               "surface { colour 1 kd 1 } }\n";
    rtpp::CompileOptions options;
    options.defines = {{"size", "2 * 3"}, {"frame", "size - 1"}};
    const std::string out = rtpp::compile(source + "", "t.rts", ".", options);
    CHECK_CONTAINS(out, "\n1 1.5 0 0 -6 ");
    // Without -D: the program's own default, and size is unknown.
    CHECK_CONTAINS(error_of(source), "unknown name 'size'");
    options.defines = {{"size", "2"}};
    CHECK_CONTAINS(rtpp::compile(source, "t.rts", ".", options), "\n1 1 0 0 -2 ");
    // Errors name the definition.
    options.defines = {{"frame", "1 +"}};
    CHECK_CONTAINS(error_of(source, options), "-D frame=1 +:1:");
    options.defines = {{"for", "1"}};
    CHECK_CONTAINS(error_of(source, options), "-D for=1: 'for' is a reserved word");
    options.defines = {{"2x", "1"}};
    CHECK_CONTAINS(error_of(source, options), "'2x' is not a name");
    options.defines = {{"n", "1 sphere { radius 1 }"}};
    CHECK_CONTAINS(error_of(source, options), "the value must be one expression");
    options.defines = {{"sphere", "1"}};
    CHECK_CONTAINS(error_of(source, options), "'sphere' is an object kind");
}

TEST(an_error_in_a_loop_names_the_pass) {
    // The body is the same on every pass, so the place alone does not say which failed.
    CHECK_EQ(error_of(kCamera + "for i = 0 to 3 {\n  for j = 0 to 1 {\n"
                                "    let y = 1 / (i - 2)\n  }\n}\n"),
             std::string("t.rts:4:15: division by zero\n"
                         "t.rts:3:3: note: in this loop, where j = 0\n"
                         "t.rts:2:1: note: in this loop, where i = 2"));
    CHECK_EQ(error_of(kCamera + "for t = 0 to 1 step 0.25 { let y = 1 / (t - 0.75) }"),
             std::string("t.rts:2:38: division by zero\n"
                         "t.rts:2:1: note: in this loop, where t = 0.75"));
}

TEST(includes_resolve_and_report_their_chain) {
    const fs::path dir = rt_test::work_dir("rtpp-include");
    fs::create_directories(dir / "lib" / "more");
    write_file(dir / "lib" / "colours.rts",
               "let red = surface { colour <1, 0, 0> kd 1 }\n"
               "include \"more/shapes.rts\"\n");
    write_file(dir / "lib" / "more" / "shapes.rts", "let ball = sphere { radius 1 }\n");
    write_file(dir / "scene.rts", kCamera + "include \"lib/colours.rts\"\nball { surface red }\n");
    const std::string out = rtpp::compile_file((dir / "scene.rts").string());
    CHECK_CONTAINS(out, "1 1 0 0 0 100 1 0 0 0 1 1 0 1");
    // The search path: a file not beside the includer is found in -I's directory.
    write_file(dir / "other.rts", kCamera + "include \"colours.rts\"\nball { surface red }\n");
    rtpp::CompileOptions options;
    options.include_dirs.push_back(dir / "lib");
    CHECK_CONTAINS(rtpp::compile_file((dir / "other.rts").string(), options), "100 1 0 0");
    CHECK_CONTAINS(error_of("include \"nowhere.rts\""),
                   "t.rts:1:1: cannot read included file 'nowhere.rts'");
    // An error in an included file names it and the chain of includes that led there.
    write_file(dir / "lib" / "more" / "shapes.rts", "let ball = sphere { radius 1 / 0 }\n");
    {
        const std::string m = file_error_of((dir / "scene.rts").string());
        CHECK_CONTAINS(m, "shapes.rts:1:30: division by zero\n  included from ");
        CHECK_CONTAINS(m,
                       "colours.rts:2:1\n  included from " + (dir / "scene.rts").string() + ":2:1");
    }
    // A cycle is an error at the include that closes it.
    write_file(dir / "a.rts", "include \"b.rts\"\n");
    write_file(dir / "b.rts", "\ninclude \"a.rts\"\n");
    CHECK_CONTAINS(file_error_of((dir / "a.rts").string()),
                   "b.rts:2:1: include cycle: 'a.rts' is already being read");
}

TEST(limits_stop_runaway_input) {
    rtpp::CompileOptions small;
    small.limits.loop_iterations = 1000;
    small.limits.objects = 10;
    small.limits.include_depth = 3;
    small.limits.nesting = 20;
    CHECK_CONTAINS(error_of(kCamera + "for i = 1 to 1e15 { }"),
                   "t.rts:2:1: this loop would run 1e+15 times, more than the 20000000");
    CHECK_CONTAINS(error_of(kCamera + "for i = 1 to 30 { for j = 1 to 40 { } }", small),
                   "t.rts:2:19: this loop would run 40 times, more than the 1000");
    CHECK_CONTAINS(error_of(kCamera + "for i = 1 to 20 { ambient { intensity 1 } }", small),
                   "t.rts:2:19: more than 10 objects written");
    CHECK_CONTAINS(
        error_of(kCamera + "let a = " + std::string(30, '(') + "1" + std::string(30, ')'), small),
        "nested more than 20 deep");
    CHECK_CONTAINS(error_of("let s = \"" + std::string(5000, 'a') + "\""),
                   "t.rts:1:9: string longer than 4096 characters");
    const fs::path dir = rt_test::work_dir("rtpp-limits");
    // (Built with join: g++ 12 warns falsely about "literal" + std::string chains.)
    for (int i = 0; i < 5; ++i)
        write_file(dir / rt_test::join('f', i, ".rts"),
                   rt_test::join("include \"f", i + 1, ".rts\"\n"));
    write_file(dir / "f5.rts", "");
    CHECK_CONTAINS(file_error_of((dir / "f0.rts").string(), small),
                   "f2.rts:1:1: includes nested more than 3 deep");
}

// The work a program does is bounded by counting it, not its loops alone: a loop within the
// iteration limit whose body is long could otherwise run for minutes. Each statement run,
// expression evaluated and field copied from a named object is one step; the counts below
// are worked out by hand from those rules.
TEST(steps_count_statements_expressions_and_copied_fields) {
    rtpp::CompileOptions small;
    // let (1), + (2), 1 (3), 2 (4): four steps, then the missing camera.
    small.limits.steps = 4;
    CHECK_CONTAINS(error_of("let a = 1 + 2", small), "t.rts:1:14: no camera in the scene");
    small.limits.steps = 3;
    CHECK_CONTAINS(error_of("let a = 1 + 2", small),
                   "t.rts:1:13: more than 3 evaluation steps (each expression evaluated, each "
                   "statement run and each field copied from a named object counts one)");
    // for (1), its bounds (2, 3), then per pass let, *, i, 2 (4 each): 43 for ten passes; the
    // 43rd is the last pass's 2, and the note names that pass.
    const std::string loop = "for i = 1 to 10 { let a = i * 2 }";
    small.limits.steps = 43;
    CHECK_CONTAINS(error_of(loop, small), "no camera in the scene");
    small.limits.steps = 42;
    const std::string message = error_of(loop, small);
    CHECK_CONTAINS(message, "t.rts:1:31: more than 42 evaluation steps");
    CHECK_CONTAINS(message, "t.rts:1:1: note: in this loop, where i = 10");
    // let (1), the mesh (2), each vertex statement, its vector and the vector's three numbers
    // (5 + 5): 12; then the statement m { } (13) copies m's two fields (15), and the emitter
    // finds no triangle.
    const std::string copy = "let m = mesh { vertex <0, 0, 0> vertex <1, 0, 0> }\nm { }";
    small.limits.steps = 14;
    CHECK_CONTAINS(error_of(copy, small), "t.rts:2:1: more than 14 evaluation steps");
    small.limits.steps = 15;
    CHECK_CONTAINS(error_of(copy, small),
                   "t.rts:2:1: mesh needs at least one vertex and one triangle");
    // The fuzz finding: a knot's loops, 360 x 46 passes of about a hundred expressions each,
    // within the fuzz case's 20,000 iterations but not its 200,000 steps.
    rtpp::CompileOptions fuzz;
    fuzz.limits.loop_iterations = 20'000;
    fuzz.limits.steps = 200'000;
    const std::string knot = file_error_of(
        (fs::path(RT_SOURCE_DIR) / "tests/fuzz/surfaces/rtpp/long-loop-body-0.66s-under-asan.rts")
            .string(),
        fuzz);
    CHECK_CONTAINS(knot, "more than 200000 evaluation steps");
    CHECK_CONTAINS(knot, "note: in this loop, where");
}

// Includes are expanded as they are parsed, so a file that includes another twice, nested,
// would parse 2^depth files: the includes read and the source read in all are bounded.
TEST(includes_and_source_read_in_all_are_bounded) {
    const fs::path dir = rt_test::work_dir("rtpp-include-total");
    for (int i = 0; i < 30; ++i)
        write_file(dir / rt_test::join('d', i, ".rts"),
                   rt_test::join("include \"d", i + 1, ".rts\"\ninclude \"d", i + 1, ".rts\"\n"));
    write_file(dir / "d30.rts", "let a = 1\n");
    CHECK_CONTAINS(file_error_of((dir / "d0.rts").string()),
                   "more than 100000 includes read in all (a file included twice counts "
                   "twice)");
    const std::string top = "include \"part.rts\"\ninclude \"part.rts\"\n";
    const std::string part = kCamera;
    write_file(dir / "top.rts", top);
    write_file(dir / "part.rts", part);
    rtpp::CompileOptions small;
    small.limits.includes = 1;
    CHECK_CONTAINS(file_error_of((dir / "top.rts").string(), small),
                   "top.rts:2:1: more than 1 includes read in all");
    small.limits.includes = 10;
    small.limits.source_total = top.size() + 2 * part.size() - 1;
    CHECK_CONTAINS(file_error_of((dir / "top.rts").string(), small),
                   rt_test::join("top.rts:2:1: more than ", small.limits.source_total,
                                 " bytes of source read in all"));
    // One byte more and both parts read (and a second camera is the error).
    small.limits.source_total += 1;
    CHECK_CONTAINS(file_error_of((dir / "top.rts").string(), small), "a second camera");
}

// The scene is held until the end (nothing is written on an error), so its size is bounded.
TEST(the_scene_written_is_bounded) {
    rtpp::CompileOptions small;
    small.limits.output_size = 400;
    const std::string scene =
        kCamera +
        "for i = 1 to 100 { sphere { centre <i, 0, 0> radius 0.5 surface { colour 1 kd 1 } } }";
    const std::string message = error_of(scene, small);
    CHECK_CONTAINS(message, "t.rts:2:20: the scene written is larger than 400 bytes");
    small.limits.output_size = 100'000;
    CHECK_EQ(error_of(scene, small), std::string());
}

// Every limit's default as docs/language.md's table gives it.
TEST(the_documented_limits_are_the_code_s) {
    const std::string page = read_file(fs::path(RT_SOURCE_DIR) / "docs" / "language.md");
    const rtpp::Limits limits;
    const auto grouped = [](long long n) {
        std::string digits = std::to_string(n), out;
        for (std::size_t i = 0; i < digits.size(); ++i) {
            if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
            out += digits[i];
        }
        return out;
    };
    CHECK_CONTAINS(
        page, "| loop iterations, all loops together | " + grouped(limits.loop_iterations) + " |");
    CHECK_CONTAINS(page,
                   "| evaluation steps, in all (see below) | " + grouped(limits.steps) + " |");
    CHECK_CONTAINS(page, "counted | " + grouped(limits.objects) + " |");
    CHECK_CONTAINS(page, "| vertices, triangles or objects in one object | " +
                             grouped(limits.list_items) + " |");
    CHECK_CONTAINS(page, "| include depth | " + grouped(limits.include_depth) + " |");
    CHECK_CONTAINS(page, "| includes read, in all | " + grouped(limits.includes) + " |");
    CHECK_CONTAINS(page, "| nesting (see below) | " + grouped(limits.nesting) + " |");
    CHECK_CONTAINS(
        page, "| a string or a name | " + std::to_string(limits.string_length) + " characters |");
    CHECK_CONTAINS(page,
                   "| one source file | " + std::to_string(limits.file_size >> 20) + " MiB |");
    CHECK_CONTAINS(page, "| source read, in all, includes counted each time | " +
                             std::to_string(limits.source_total >> 20) + " MiB |");
    CHECK_CONTAINS(page,
                   "| the scene written | " + std::to_string(limits.output_size >> 30) + " GiB |");
    CHECK_EQ(limits.file_size % (1u << 20), std::size_t{0});
    CHECK_EQ(limits.source_total % (1u << 20), std::size_t{0});
    CHECK_EQ(limits.output_size % (std::size_t{1} << 30), std::size_t{0});
}

// The time is printed, not checked: timings belong in benchmarks, and a shared machine or a
// sanitizer build can take many times as long.
TEST(a_million_objects_compile) {
    const auto start = std::chrono::steady_clock::now();
    const std::string out =
        rtpp::compile(kCamera +
                          "let red = surface { colour <1, 0, 0> kd 1 }\n"
                          "for i = 0 to 999 { for j = 0 to 999 {\n"
                          "  sphere { radius 0.4 centre <i, 0, j> surface red } } }\n",
                      "million.rts", ".");
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "  1,000,000 spheres: " << seconds << " s, " << out.size() / 1000000 << " MB\n";
    std::istringstream in(out);
    CHECK_EQ(rt::SceneReader(in, "million", {}).read_scene().objects.size(), 1000000u);
}

TEST(rt_names_the_readable_source_through_line_markers) {
    const fs::path dir = rt_test::work_dir("rtpp-markers");
    // A degenerate triangle made by a loop: only rt finds it, and names the .rts line.
    write_file(dir / "s.rts", kCamera +
                                  "let m = surface { colour 1 kd 1 }\n"
                                  "for i = 0 to 2 {\n"
                                  "    triangle { vertex x vertex x * i vertex y surface m }\n"
                                  "}\n");
    const std::string command = "cd '" + dir.string() + "' && '" RTPP_BINARY "' s.rts -o s.in";
    CHECK_EQ(std::system(command.c_str()), 0);
    const rt_test::RunResult checked = rt_test::run_rt(dir, "-r s.in");
    CHECK_EQ(checked.status, 1);
    CHECK_CONTAINS(checked.err, "s.rts:4:");
    CHECK_CONTAINS(checked.err, "triangle");
}

TEST(the_command_line_follows_rts_conventions) {
    const fs::path dir = rt_test::work_dir("rtpp-cli");
    const auto run = [&](const std::string& args) {
        const std::string command = "cd '" + dir.string() + "' && '" RTPP_BINARY "' " + args +
                                    " >out.txt 2>err.txt; echo $? >status.txt";
        CHECK_EQ(std::system(command.c_str()), 0);
        return std::atoi(read_file(dir / "status.txt").c_str());
    };
    write_file(dir / "ok.rts", kCamera);
    write_file(dir / "bad.rts", "sphere {");
    CHECK_EQ(run("ok.rts"), 0);
    CHECK_CONTAINS(read_file(dir / "out.txt"), "102 0 0 5");
    CHECK_EQ(run("< ok.rts"), 0);
    CHECK_CONTAINS(read_file(dir / "out.txt"), "#line 1 \"<stdin>\"");
    CHECK_EQ(run("ok.rts | '" RT_BINARY "' -r"), 0);
    CHECK_CONTAINS(read_file(dir / "out.txt"), "<stdin>: 0 objects, 0 lights, 4x4");
    write_file(dir / "keep.in", "old");
    CHECK_EQ(run("bad.rts -o keep.in"), 1);
    CHECK_CONTAINS(read_file(dir / "err.txt"), "bad.rts:1:9: end of file inside sphere");
    CHECK_EQ(read_file(dir / "keep.in"), std::string("old"));
    CHECK_EQ(run("ok.rts -o keep.in"), 0);
    CHECK_CONTAINS(read_file(dir / "keep.in"), "102 0 0 5");
    CHECK_EQ(run("--help"), 0);
    CHECK_CONTAINS(read_file(dir / "out.txt"), "usage: rtpp");
    CHECK_EQ(run("--version"), 0);
    CHECK_CONTAINS(read_file(dir / "out.txt"), "rtpp ");
    CHECK_EQ(run("--bogus"), 2);
    CHECK_CONTAINS(read_file(dir / "err.txt"), "rtpp: unknown option '--bogus'");
    CHECK_EQ(run("-I"), 2);
    CHECK_CONTAINS(read_file(dir / "err.txt"), "rtpp: -I needs a value");
    CHECK_EQ(run("--help=1"), 2);
    CHECK_CONTAINS(read_file(dir / "err.txt"), "rtpp: --help takes no value");
    CHECK_EQ(run("ok.rts ok.rts"), 2);
    CHECK_CONTAINS(read_file(dir / "err.txt"), "more than one scene given ('ok.rts' and 'ok.rts')");
    // After "--" a name starting with '-' is the scene; values may be joined to -o and -I.
    write_file(dir / "-dash.rts", kCamera);
    CHECK_EQ(run("-okeep.in -- -dash.rts"), 0);
    CHECK_CONTAINS(read_file(dir / "keep.in"), "102 0 0 5");
    CHECK_EQ(run("missing.rts"), 1);
    CHECK_CONTAINS(read_file(dir / "err.txt"), "missing.rts: cannot open");
}

namespace {

// A scene of `n` x 1000 spheres: big enough that writing it takes a while.
std::string many_spheres(int n) {
    return kCamera + "let s = surface { colour 1 kd 1 }\nfor i = 1 to " + std::to_string(n) +
           " { for j = 1 to 1000 { sphere { radius 0.1 centre <i, j, 0> surface s } } }\n";
}

// Runs `rtpp args` in `dir` through the shell; its exit status.
int run_rtpp(const fs::path& dir, const std::string& args) {
    const std::string command = "cd '" + dir.string() + "' && '" RTPP_BINARY "' " + args +
                                " 2>>err.txt; echo $? >status.txt";
    if (std::system(command.c_str()) != 0) return -1;
    return std::atoi(read_file(dir / "status.txt").c_str());
}

}  // namespace

// As under make -j: two rtpp writing the same file at once each write a temporary file of
// their own, so the one renamed last is whole and nothing else is left.
TEST(two_rtpp_writing_one_output_leave_one_complete_file) {
    const fs::path dir = rt_test::work_dir("rtpp-concurrent");
    write_file(dir / "s.rts", many_spheres(200));
    CHECK_EQ(run_rtpp(dir, "s.rts -o alone.in"), 0);
    const std::string alone = read_file(dir / "alone.in");
    CHECK(alone.size() > 10000000);
    // Fewer rounds under ASan, where each takes six times as long.
    for (int round = 0; round < (RT_MEASURES_MEMORY ? 5 : 2); ++round) {
        const std::string rtpp = "'" RTPP_BINARY "' s.rts -o out.in";
        const std::string command = "cd '" + dir.string() + "' && { " + rtpp + " & a=$!; " + rtpp +
                                    " & b=$!; wait $a; x=$?; wait $b; echo $x $? " +
                                    ">both.txt; } 2>err.txt";
        CHECK_EQ(std::system(command.c_str()), 0);
        CHECK_EQ(read_file(dir / "both.txt"), std::string("0 0\n"));
        CHECK_EQ(read_file(dir / "err.txt"), std::string());
        CHECK(read_file(dir / "out.in") == alone);
        CHECK(litter(dir).empty());
    }
}

TEST(rtpp_keeps_the_outputs_mode_and_refuses_its_scene_as_output) {
    const fs::path dir = rt_test::work_dir("rtpp-mode");
    write_file(dir / "s.rts", kCamera);
    write_file(dir / "out.in", "old");
    ::chmod((dir / "out.in").c_str(), 0640);
    CHECK_EQ(run_rtpp(dir, "s.rts -o out.in"), 0);
    CHECK_CONTAINS(read_file(dir / "out.in"), "102 0 0 5");
    struct stat st {};
    CHECK_EQ(::stat((dir / "out.in").c_str(), &st), 0);
    CHECK_EQ(st.st_mode & 07777, static_cast<mode_t>(0640));
    // The scene is never written over, whatever it is called.
    CHECK_EQ(run_rtpp(dir, "s.rts -o ./s.rts"), 1);
    CHECK_CONTAINS(read_file(dir / "err.txt"),
                   "./s.rts: cannot write the output file: it is the scene file 's.rts'");
    CHECK_EQ(read_file(dir / "s.rts"), kCamera);
    // A missing directory is found before the scene is compiled.
    CHECK_EQ(run_rtpp(dir, "missing.rts -o no/such.in"), 1);
    CHECK_CONTAINS(read_file(dir / "err.txt"),
                   "no/such.in: cannot write the output file: the directory 'no' does not exist");
    // A device is written in place.
    CHECK_EQ(run_rtpp(dir, "s.rts -o /dev/null"), 0);
    CHECK(litter(dir).empty());
}

TEST(an_interrupted_rtpp_leaves_no_temporary_file) {
    const fs::path dir = rt_test::work_dir("rtpp-signal");
    write_file(dir / "big.rts", many_spheres(1000));
    write_file(dir / "out.in", "old");
    const std::string dir_text = dir.string();
    const pid_t pid = ::fork();
    if (pid == 0) {
        const int err = ::open((dir_text + "/err.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (err < 0 || ::chdir(dir_text.c_str()) != 0) ::_exit(125);
        ::dup2(err, STDERR_FILENO);
        ::execl(RTPP_BINARY, RTPP_BINARY, "big.rts", "-o", "out.in", static_cast<char*>(nullptr));
        ::_exit(127);
    }
    // The temporary file exists from before the scene is compiled.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (litter(dir).empty() && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    CHECK(!litter(dir).empty());
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ::kill(pid, SIGTERM);
    int status = 0;
    ::waitpid(pid, &status, 0);
    CHECK(WIFSIGNALED(status));
    CHECK_EQ(WIFSIGNALED(status) ? WTERMSIG(status) : 0, SIGTERM);
    CHECK_EQ(read_file(dir / "err.txt"), std::string("rtpp: interrupted\n"));
    CHECK(litter(dir).empty());
    CHECK_EQ(read_file(dir / "out.in"), std::string("old"));
}

TEST(background_writes_115_once) {
    CHECK_EQ(last_line("background { colour <0.25, 0.5, 1> }"), std::string("115 0.25 0.5 1"));
    CHECK_EQ(last_line("background { colour 0.5 }"), std::string("115 0.5 0.5 0.5"));
    CHECK_EQ(error_of(kCamera + "background { colour 0 }\nbackground { colour 1 }\n"),
             std::string("t.rts:3:1: a second background; a scene has at most one, the first is "
                         "at t.rts:2:1"));
    CHECK_CONTAINS(error_of(kCamera + "background { colour 0 translate <1, 0, 0> }"),
                   "t.rts:2:23: a background cannot be transformed");
    CHECK_CONTAINS(error_of(kCamera + "group { background { colour 0 } translate <1, 0, 0> }"),
                   "t.rts:2:9: a background cannot be transformed");
    CHECK_CONTAINS(error_of(kCamera + "background { }"), "colour");
    // What rtpp writes, rt reads: the background is the scene's.
    std::istringstream in(
        rtpp::compile(kCamera + "background { colour <0.25, 0.5, 1> }", "t.rts", "."));
    const rt::Scene scene = rt::read_scene(in, "t.in");
    CHECK(scene.background.has_value());
}
