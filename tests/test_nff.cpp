// rtpp's NFF front end: each entity against the numeric text it must write, the viewer's
// half-pixel shift against NFF's pixel-centre rays, the cone from two radii against closed
// forms (and through rt's own cone), pp patches gathered into smooth meshes, errors with
// their places, and a million spheres streamed through without being held.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <sstream>
#include <streambuf>
#include <string>
#include <vector>

#include "check.h"
#include "rt/viewer.h"
#include "rtpp/nff.h"
#include "scene_util.h"

using rt::Vec3;

namespace {

const std::string kView = "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 4 4\n";
const std::string kFill = "f 1 0.5 0.25 0.75 0.5 20 0 1\n";

std::string translate(const std::string& nff, const rtpp::NffOptions& options = {}) {
    std::istringstream in(nff);
    std::ostringstream out;
    rtpp::translate_nff(in, "t.nff", out, options);
    return out.str();
}

// The written lines without comments, markers and blank lines.
std::vector<std::string> body(const std::string& nff, const rtpp::NffOptions& options = {}) {
    std::istringstream in(translate(nff, options));
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);)
        if (!line.empty() && line[0] != '#') lines.push_back(line);
    return lines;
}

// The lines an entity writes after a viewpoint and a surface (102 and 105 are dropped).
std::vector<std::string> object_lines(const std::string& entity) {
    std::vector<std::string> lines = body(kView + kFill + entity);
    std::vector<std::string> kept;
    for (const std::string& l : lines)
        if (l.rfind("105 ", 0) != 0 && l != "102" && l.find(' ') != std::string::npos &&
            l.size() > 0)
            kept.push_back(l);
    // The viewer's own lines: eye, look-at, x and y, resolution.
    return std::vector<std::string>(kept.begin() + 4, kept.end());
}

std::string error_of(const std::string& nff, const rtpp::NffOptions& options = {}) {
    try {
        translate(nff, options);
    } catch (const rtpp::CompileError& e) {
        return e.what();
    }
    return "";
}

std::string shortest(double v) {
    char text[32];
    const auto r = std::to_chars(text, text + sizeof text, v);
    return std::string(text, r.ptr);
}

std::vector<double> numbers_in(const std::string& text) {
    std::istringstream in(text);
    std::vector<double> v;
    for (double d; in >> d;) v.push_back(d);
    return v;
}

// rt's viewer as the translation writes it: the numbers after 102, up to the resolution.
rt::Viewer viewer_of(const std::string& nff) {
    std::istringstream in(translate(nff));
    std::string all, line;
    while (std::getline(in, line))
        if (!line.empty() && line[0] != '#') all += line + " ";
    std::vector<double> n = numbers_in(all.substr(all.find("102 ") + 4));
    rt::Viewer v;
    v.eye = {n[0], n[1], n[2]};
    v.look_at = {n[3], n[4], n[5]};
    v.x = {n[6], n[7], n[8]};
    v.y = {n[9], n[10], n[11]};
    v.xres = static_cast<int>(n[12]);
    v.yres = static_cast<int>(n[13]);
    return v;
}

std::string view_text(const Vec3& from, const Vec3& at, const Vec3& up, double angle, int xres,
                      int yres) {
    std::ostringstream s;
    s.precision(17);
    s << "v\nfrom " << from.x << ' ' << from.y << ' ' << from.z << "\nat " << at.x << ' ' << at.y
      << ' ' << at.z << "\nup " << up.x << ' ' << up.y << ' ' << up.z << "\nangle " << angle
      << "\nhither 1\nresolution " << xres << ' ' << yres << "\n";
    return s.str();
}

}  // namespace

TEST(background_fill_sphere_and_polygon_write_their_ids_term_by_term) {
    CHECK_EQ(body(kView + "b 0.1 0.2 0.3\n").back(), std::string("115 0.1 0.2 0.3"));
    // f r g b Kd Ks Shine T ior -> 100's colour; ks; ke; kd; kt; ior, made the default.
    const std::vector<std::string> f = body(kView + "f 1 0.5 0.25 0.75 0.5 20 0.125 1.5\n");
    CHECK_EQ(f.back(), std::string("105 100 1 0.5 0.25 0.5 20 0.75 0.125 1.5"));
    CHECK_EQ(object_lines("s 1 2 3 0.5\n").at(0), std::string("1 0.5 1 2 3 106"));
    // A negative radius (only the inside seen) is the same sphere to rt, which is two-sided.
    CHECK_EQ(object_lines("s 1 2 3 -0.5\n").at(0), std::string("1 0.5 1 2 3 106"));
    // Numbers are written back as read: the shortest text of the same double.
    CHECK_EQ(object_lines("s 0.272166 1e-3 +2 0.0555556\n").at(0),
             std::string("1 0.0555556 0.272166 0.001 2 106"));
    // A polygon's vertices stay on their lines, so rt's messages point at them.
    const std::vector<std::string> p = object_lines("p 3\n0 0 0\n1 0 0\n0 1 0\n");
    CHECK_EQ(p.size(), 4u);
    CHECK_EQ(p.at(0), std::string("11 3"));
    CHECK_EQ(p.at(1), std::string("0 0 0"));
    CHECK_EQ(p.at(3), std::string("0 1 0 106"));
}

TEST(equal_radii_make_a_cylinder_and_unequal_ones_a_cone) {
    CHECK_EQ(object_lines("c\n0 0 0 0.5\n0 0 2 0.5\n").at(0),
             std::string("9 0.5 0 1 0 0 0 0 0 2 106"));
    CHECK_EQ(object_lines("c\n0 0 0 -0.5\n1 2 2 -0.5\n").at(0),
             std::string("9 0.5 0 1 0 0 0 1 2 2 106"));
    // Base radius 5, apex radius 1, 3 apart: the radius falls by 4 over 3, cos = 3/5; the
    // axis, scaled to 3/4 per unit of radius, points from the apex to the base, and the true
    // apex lies 5 * 3/4 beyond the base.
    CHECK_EQ(object_lines("c\n1 2 3 5\n1 2 6 1\n").at(0),
             std::string("8 0.6 1 5 1 2 6.75 0 0 -0.75 106"));
}

TEST(lights_share_white_as_the_spd_does) {
    // No light yet known when the first is read: lights are written at the end.
    const std::vector<std::string> one = body(kView + "l 1 2 3\n" + kFill + "s 0 0 0 1\n");
    CHECK_EQ(one.back(), std::string("104 1 2 3 1 1 1"));
    const std::vector<std::string> two = body(kView + "l 1 2 3\nl 4 5 6 0.5 0 1\n");
    const std::string s = shortest(1 / std::sqrt(2.0));
    CHECK_EQ(two.at(two.size() - 2), "104 1 2 3 " + s + " " + s + " " + s);
    // A colour given is scaled the same way: "l ... 1 1 1" is the same as no colour.
    CHECK_EQ(two.back(), "104 4 5 6 " + shortest(0.5 / std::sqrt(2.0)) + " 0 " + s);
    const std::vector<std::string> four =
        body(kView + "l 0 0 1\nl 0 0 2\nl 0 0 3\nl 0 0 4 1 1 1\n");
    CHECK_EQ(four.back(), std::string("104 0 0 4 0.5 0.5 0.5"));
    // Each light keeps its own line: a marker names it.
    CHECK_CONTAINS(translate(kView + "l 1 2 3\n" + kFill + "s 0 0 0 1\n"),
                   "#line 8 \"t.nff\"\n104 1 2 3 1 1 1\n");
}

TEST(output_lines_follow_the_source_lines) {
    const std::string out = translate(kView + "# a comment\n\n" + kFill + "s 0 0 0 1  # more\n");
    std::istringstream in(out);
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    CHECK_EQ(lines.at(0), std::string("# Written by rtpp from t.nff; edit that, not this."));
    CHECK_EQ(lines.at(1), std::string("#line 1 \"t.nff\""));
    // Output line k + 1 is source line k - 1 from here on.
    CHECK_EQ(lines.at(2), std::string("102"));
    CHECK_EQ(lines.at(3), std::string("0 0 5"));
    CHECK_EQ(lines.at(7), std::string(""));  // hither is not used
    CHECK_EQ(lines.at(8), std::string("4 4"));
    CHECK_EQ(lines.at(11), std::string("105 100 1 0.5 0.25 0.5 20 0.75 0 1"));
    CHECK_EQ(lines.at(12), std::string("1 1 0 0 0 106"));
    CHECK_EQ(lines.size(), 13u);
}

TEST(rt_reads_the_translation_and_names_the_nff_source_in_its_errors) {
    const std::string scene = translate(kView + "b 0 0 0\nl 1 1 1\n" + kFill +
                                        "s 0 0 0 1\nc\n0 0 0 1\n0 0 1 0.5\nc\n0 0 0 1\n0 1 0 1\n"
                                        "p 4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n");
    // Today's rt has no background (115) yet: read the rest.
    std::string without_background = scene;
    const std::size_t at = scene.find("115 ");
    without_background.erase(at, scene.find('\n', at) - at);
    const rt::Scene s = rt_test::parse_scene(without_background);
    CHECK_EQ(s.lights.size(), 1u);
    CHECK_EQ(s.viewer.xres, 4);
    // A polygon that is not flat is rt's to refuse; its message names the NFF line.
    const std::string bad = translate(kView + kFill + "p 4\n0 0 0\n1 0 0\n1 1 1\n0 1 0\n");
    CHECK_CONTAINS(rt_test::scene_error(bad), "t.nff:13:1: polygon vertex 3 is not in the plane");
}

TEST(the_viewer_puts_rts_corner_rays_through_nffs_pixel_centres) {
    struct Case {
        Vec3 from, at, up;
        double angle;
        int xres, yres;
    };
    const Case cases[] = {
        {{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 45, 5, 5},
        {{2.1, 1.3, 1.7}, {0, 0, 0}, {0, 0, 1}, 45, 4, 4},
        // Up not square to the view, the at point far off, a wide image and a tall one.
        {{1, -2, 3}, {8, 5, -1}, {0.3, 0.2, 1}, 60, 7, 3},
        {{1, -2, 3}, {8, 5, -1}, {0.3, 0.2, 1}, 30, 2, 6},
    };
    for (const Case& c : cases) {
        const rt::Viewer v = viewer_of(view_text(c.from, c.at, c.up, c.angle, c.xres, c.yres));
        // NFF's centre ray through pixel (X, Y): the angle spans the centres of the first and
        // last pixels of the longer side; pixels are square.
        const Vec3 d = normalized(c.at - c.from);
        const Vec3 r = normalized(cross(d, c.up));
        const Vec3 u = cross(r, d);
        const int n = std::max(c.xres, c.yres);
        const double pitch = 2 * std::tan(c.angle * std::numbers::pi / 360) / (n - 1);
        rt::Viewer unshifted;
        unshifted.eye = c.from;
        unshifted.look_at = c.at;
        unshifted.x = r * (c.xres * pitch / 2);
        unshifted.y = u * (c.yres * pitch / 2);
        unshifted.xres = c.xres;
        unshifted.yres = c.yres;
        for (int Y = 0; Y < c.yres; ++Y) {
            for (int X = 0; X < c.xres; ++X) {
                const Vec3 nff = normalized(d + (X - (c.xres - 1) / 2.0) * pitch * r +
                                            ((c.yres - 1) / 2.0 - Y) * pitch * u);
                const rt::Ray ray = v.primary_ray(X, Y);
                CHECK_NEAR(ray.origin, c.from, 1e-15);
                CHECK_NEAR(ray.direction, nff, 1e-12);
                // Unshifted, the same rays are rt's through corner + half a pixel.
                CHECK_NEAR(unshifted.primary_ray(X + 0.5, Y + 0.5).direction, nff, 1e-12);
            }
        }
        if (c.xres % 2 == 1 && c.yres % 2 == 1)  // the centre pixel looks straight at `at`
            CHECK_NEAR(v.primary_ray(c.xres / 2, c.yres / 2).direction, d, 1e-14);
        // The angle between the outermost centre rays of the longer side is NFF's angle.
        const bool wide = c.xres >= c.yres;
        const Vec3 first = v.primary_ray(0, 0).direction;
        const Vec3 last = v.primary_ray(wide ? c.xres - 1 : 0, wide ? 0 : c.yres - 1).direction;
        const Vec3 mid_first = wide ? first - dot(first, u) * u : first - dot(first, r) * r;
        const Vec3 mid_last = wide ? last - dot(last, u) * u : last - dot(last, r) * r;
        CHECK_NEAR(
            std::acos(dot(normalized(mid_first), normalized(mid_last))) * 180 / std::numbers::pi,
            c.angle, 1e-9);
        // rt's pixels are square: |x| : |y| = xres : yres.
        CHECK_NEAR(length(v.x) / length(v.y), double(c.xres) / c.yres, 1e-12);
    }
}

TEST(the_cone_from_two_radii_is_the_closed_form_cone) {
    struct Case {
        Vec3 base;
        double rb;
        Vec3 apex;
        double ra;
    };
    const Case cases[] = {{{0, 0, 0}, 2, {0, 0, 1}, 1},
                          {{1, 2, 3}, 0.5, {-2, 4, 1}, 0},
                          {{1, 2, 3}, 0.25, {-2, 4, 1}, 3},  // wider at the "apex"
                          {{0, 0, 0}, 1, {0, 0, 1e-3}, 1e3}};
    for (const Case& c : cases) {
        const rtpp::NffCone k = rtpp::nff_cone(c.base, c.rb, c.apex, c.ra);
        const double len = length(c.apex - c.base);
        // cos(half-angle) from the slope of the radius along the axis.
        CHECK_NEAR(k.alpha, len / std::sqrt(len * len + (c.rb - c.ra) * (c.rb - c.ra)), 1e-15);
        CHECK_EQ(k.start, std::min(c.rb, c.ra));
        CHECK_EQ(k.finish, std::max(c.rb, c.ra));
        const Vec3 a_hat = normalized(k.axis);
        const rt_test::Frame frame = rt_test::frame_around(c.apex - c.base);
        for (double s : {0.0, 0.25, 0.5, 1.0}) {
            // The ring a fraction s of the way from base to apex, radius linear between.
            const Vec3 centre = c.base + s * (c.apex - c.base);
            const double radius = c.rb + s * (c.ra - c.rb);
            for (double phi : {0.0, 1.0, 2.5, 4.0}) {
                const Vec3 x =
                    centre + radius * (std::cos(phi) * frame.e1 + std::sin(phi) * frame.e2);
                const Vec3 w = x - k.apex;
                // On the double cone ((x - c).a^)^2 = alpha^2 |x - c|^2 ...
                const double along = dot(w, a_hat) * dot(w, a_hat);
                CHECK_NEAR(along, k.alpha * k.alpha * dot(w, w), 1e-9 * along);
                // ... and inside the extent, at the parameter of its radius.
                CHECK_NEAR(dot(w, k.axis) / dot(k.axis, k.axis), radius, 1e-9 * (1 + radius));
            }
        }
    }
}

TEST(rts_cone_built_from_nff_radii_is_hit_where_the_radius_says) {
    // Base radius 2 at z = 0, apex radius 0.5 at z = 3: radius 2 - z/2. Rays along -x.
    const std::string line = object_lines("c\n0 0 0 2\n0 0 3 0.5\n").at(0);
    const rt::Shape cone = rt_test::parse_shape(line.substr(0, line.rfind(" 106")));
    for (double z : {0.1, 1.0, 2.0, 2.9}) {
        rt::Hit hit;
        CHECK(cone.intersect({{10, 0, z}, {-1, 0, 0}}, {1e-9, rt::kInfinity}, hit));
        CHECK_NEAR(hit.t, 10 - (2 - z / 2), 1e-9);
    }
    // Past either end the cut cone is not there (the ray meets only the far wall's
    // continuation, which is cut too).
    for (double z : {-0.1, 3.1}) {
        rt::Hit hit;
        CHECK(!cone.intersect({{10, 0, z}, {-1, 0, 0}}, {1e-9, rt::kInfinity}, hit));
    }
}

TEST(consecutive_patches_gather_into_one_smooth_mesh) {
    const std::string tri = "pp 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n";
    const std::string quad = "pp 4\n0 0 1 0 0 2\n1 0 1 0 0 2\n1 1 1 0 0 2\n0 1 1 0 0 2\n";
    const std::vector<std::string> m = object_lines(tri + "# between\n" + quad);
    // One mesh: 7 vertices, each on its line; the quad fanned from its first vertex.
    CHECK_EQ(m.at(0), std::string("16 7 3"));
    CHECK_EQ(m.at(1), std::string("0 0 0 0 0 1"));
    CHECK_EQ(m.at(7), std::string("0 1 1 0 0 2 0 1 2 3 4 5 3 5 6 106"));
    CHECK_EQ(m.size(), 8u);
    // Anything else in between ends the mesh: an object, or a new surface.
    const std::vector<std::string> split = object_lines(tri + "s 0 0 0 1\n" + tri);
    CHECK_EQ(split.at(0), std::string("16 3 1"));
    CHECK_EQ(split.at(3), std::string("0 1 0 0 0 1 0 1 2 106"));
    CHECK_EQ(split.at(4), std::string("1 1 0 0 0 106"));
    CHECK_EQ(split.at(5), std::string("16 3 1"));
    const std::vector<std::string> refill = body(kView + kFill + tri + kFill + tri);
    int meshes = 0;
    for (const std::string& l : refill) meshes += l.rfind("16 ", 0) == 0;
    CHECK_EQ(meshes, 2);
    // Past the mesh size bound, a new mesh starts.
    rtpp::NffOptions small;
    small.max_mesh_vertices = 6;
    const std::vector<std::string> bounded = body(kView + kFill + tri + quad + tri, small);
    std::vector<std::string> heads;
    for (const std::string& l : bounded)
        if (l.rfind("16 ", 0) == 0) heads.push_back(l);
    CHECK_EQ(heads.size(), 3u);
    CHECK_EQ(heads.at(0), std::string("16 3 1"));
    CHECK_EQ(heads.at(1), std::string("16 4 2"));
    CHECK_EQ(heads.at(2), std::string("16 3 1"));
}

TEST(errors_name_the_file_line_and_column) {
    const std::string head = kView + kFill;  // 8 lines
    CHECK_EQ(error_of(head + "q 1 2\n"),
             std::string("t.nff:9:1: unknown NFF entity 'q' (NFF has v, b, l, f, c, s, p, pp)"));
    CHECK_EQ(error_of(head + "s 1 2 3\n"),
             std::string("t.nff:9:8: end of file: expected s radius"));
    CHECK_EQ(error_of(head + "s 1 2 3 0\n"), std::string("t.nff:9:9: s radius must not be 0"));
    CHECK_EQ(error_of(head + "s 1 x 3 1\n"),
             std::string("t.nff:9:5: expected s centre y, got 'x'"));
    CHECK_EQ(error_of(head + "s 1 2 3 1e999\n"),
             std::string("t.nff:9:9: s radius is out of range: '1e999'"));
    CHECK_EQ(error_of(head + "s 1 2 3 nan\n"),
             std::string("t.nff:9:9: s radius must be finite, got 'nan'"));
    CHECK_EQ(error_of(head + "p 2\n0 0 0\n1 0 0\n"),
             std::string("t.nff:9:3: p vertex count must be a whole number from 3 to 1048576, "
                         "got '2'"));
    CHECK_EQ(error_of(head + "p 3.5\n"),
             std::string("t.nff:9:3: p vertex count must be a whole number from 3 to 1048576, "
                         "got '3.5'"));
    CHECK_EQ(error_of(head + "pp 3\n0 0 0 0 0 1\n1 0 0  0 0 0\n0 1 0 0 0 1\n"),
             std::string("t.nff:11:8: pp vertex 2 normal must not be zero"));
    CHECK_EQ(error_of(head + "c\n0 0 0 1\n0 0 1 -1\n"),
             std::string("t.nff:11:7: c radii must have the same sign (both negative: seen "
                         "from inside)"));
    CHECK_EQ(error_of(head + "c\n0 0 0 0\n0 0 1 0\n"),
             std::string("t.nff:11:7: c radii must not both be 0"));
    CHECK_EQ(error_of(head + "c\n0 0 0 1\n0 0 0 0.5\n"),
             std::string("t.nff:11:1: c apex must differ from base"));
    CHECK_EQ(error_of(kView + "s 0 0 0 1\n"),
             std::string("t.nff:8:1: 's' before any 'f': NFF gives each object the last 'f' "
                         "before it"));
    CHECK_EQ(error_of(kView + "f 1 1 -1 1 0 1 0 1\n"),
             std::string("t.nff:8:7: f colour blue must be >= 0, got '-1'"));
    CHECK_EQ(error_of(kView + "f 1 1 1 1 0 1 0.5 0\n"),
             std::string("t.nff:8:19: f index of refraction must be > 0 when T > 0, got '0'"));
    CHECK_EQ(error_of(kView + "b 1 1\n"),
             std::string("t.nff:8:6: end of file: expected b colour blue"));
    CHECK_EQ(error_of(kView + "b 1 1 1\nb 0 0 0\n"),
             std::string("t.nff:9:1: a second 'b': a scene has one background"));
    CHECK_EQ(error_of(kView + kView), std::string("t.nff:8:1: a second 'v': an NFF file has one "
                                                  "viewpoint"));
    CHECK_EQ(error_of(kFill + "s 0 0 0 1\n"),
             std::string("t.nff:2:10: no 'v' viewpoint in the file; rt needs one"));
    CHECK_EQ(error_of("v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nhither 1\nresolution 4 4\ns 0 0 0 1\n"),
             std::string("t.nff:7:1: v: missing 'angle' (a viewpoint has from, at, up, angle, "
                         "hither and resolution)"));
    CHECK_EQ(error_of("v\nfrom 0 0 5\nfrom 0 0 5\n"), std::string("t.nff:3:1: v: a second 'from'"));
    CHECK_EQ(error_of("v\nfrom 0 0 5\nat 0 0 5\nup 0 1 0\nangle 45\nresolution 4 4\n"),
             std::string("t.nff:3:1: v: 'at' must differ from 'from'"));
    CHECK_EQ(error_of("v\nfrom 0 0 5\nat 0 0 0\nup 0 0 2\nangle 45\nresolution 4 4\n"),
             std::string("t.nff:4:1: v: 'up' must not be zero or along the line of sight"));
    CHECK_EQ(error_of("v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 180\nresolution 4 4\n"),
             std::string("t.nff:5:7: v angle must be between 0 and 180 degrees, got '180'"));
    CHECK_EQ(error_of("v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nresolution 0 4\n"),
             std::string("t.nff:6:12: v resolution x must be a whole number from 1 to 1000000, "
                         "got '0'"));
    rtpp::NffOptions short_lines;
    short_lines.max_line_length = 16;
    CHECK_EQ(error_of(kView + "# " + std::string(40, 'x') + "\n", short_lines),
             std::string("t.nff:8:17: line longer than 16 bytes"));
    rtpp::NffOptions few_lights;
    few_lights.max_lights = 2;
    CHECK_EQ(error_of(kView + "l 0 0 1\nl 0 0 2\nl 0 0 3\n", few_lights),
             std::string("t.nff:10:1: more than 2 lights"));
    // A long token is cut in the message.
    CHECK_CONTAINS(error_of(head + std::string(100, 'z') + "\n"),
                   "'" + std::string(40, 'z') + "...'");
}

TEST(crlf_tabs_and_comments_anywhere_are_read) {
    const std::vector<std::string> b = body(
        "v\r\nfrom 0 0 5\r\nat 0 0 0 # look here\r\nup\t0 1 0\r\nangle 45\r\n"
        "hither 1\r\nresolution 4 4\r\n" +
        kFill + "s\t0 0 0 1#no space\r\n");
    CHECK_EQ(b.back(), std::string("1 1 0 0 0 106"));
}

namespace {

// NFF text made as it is read: a viewpoint, a fill, then `count` spheres.
class GeneratedNff : public std::streambuf {
  public:
    explicit GeneratedNff(long count) : count_(count) {
        line_ = kView + kFill;
        set();
    }

  protected:
    int_type underflow() override {
        if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
        if (next_ >= count_) return traits_type::eof();
        line_ =
            "s " + std::to_string(next_ % 1000) + " " + std::to_string(next_ / 1000) + " 0 0.25\n";
        ++next_;
        set();
        return traits_type::to_int_type(*gptr());
    }

  private:
    void set() { setg(line_.data(), line_.data(), line_.data() + line_.size()); }
    long count_;
    long next_ = 0;
    std::string line_;
};

// Counts lines and bytes written, keeping none of them.
class CountingSink : public std::streambuf {
  public:
    long lines = 0;
    long bytes = 0;
    std::string last_line, current;

  protected:
    int_type overflow(int_type c) override {
        if (c != traits_type::eof()) put(static_cast<char>(c));
        return c;
    }
    std::streamsize xsputn(const char* s, std::streamsize n) override {
        for (std::streamsize i = 0; i < n; ++i) put(s[i]);
        return n;
    }

  private:
    void put(char c) {
        ++bytes;
        if (c == '\n') {
            ++lines;
            last_line = current;
            current.clear();
        } else if (current.size() < 200) {
            current += c;
        }
    }
};

}  // namespace

TEST(a_million_spheres_stream_through) {
    constexpr long kSpheres = 1'000'000;
    GeneratedNff source(kSpheres);
    std::istream in(&source);
    CountingSink sink;
    std::ostream out(&sink);
    rtpp::translate_nff(in, "big.nff", out);
    // The header and the first marker, the 8 lines of viewpoint and fill, then one line for
    // each sphere.
    CHECK_EQ(sink.lines, 2 + 8 + kSpheres);
    CHECK_EQ(sink.last_line, std::string("1 0.25 999 999 0 106"));
}
