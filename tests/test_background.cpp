// The background (ID 115): what a ray that hits nothing brings back, checked pixel by pixel
// against values worked out by hand.
#include <cmath>
#include <string>

#include "cli_util.h"
#include "rt/optics.h"
#include "rt/trace.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

TEST(background_is_read_once_and_stored) {
    const Scene none = parse_scene(kTestViewer);
    CHECK(!none.background.has_value());
    const Scene scene = parse_scene(join(kTestViewer, "115 0.25 0.5 0.75\n"));
    CHECK(scene.background.has_value());
    CHECK_EQ(show(*scene.background), show(Spectrum(0.25, 0.5, 0.75)));
    // Like the ambient intensity it stands in for, any finite numbers.
    const Scene odd = parse_scene(join(kTestViewer, "115 -1 0 1e300\n"));
    CHECK_EQ(show(*odd.background), show(Spectrum(-1, 0, 1e300)));
}

TEST(a_primary_ray_that_misses_returns_exactly_the_background) {
    // An empty scene, and one with an ambient light: the background replaces the ambient
    // intensity, bit for bit, in every pixel; a supersampled pixel is the mean of nine such
    // values (sum times 1/9, so to rounding).
    for (const char* ambient : {"", "103 0.3 0.3 0.3\n"}) {
        const Scene scene = parse_scene(join(kTestViewer, ambient, "115 0.1 0.2 0.7\n"));
        for (int samples : {1, 3}) {
            RenderOptions options;
            options.samples = samples;
            Tracer tracer(scene, options);
            for (int y = 0; y < 4; ++y)
                for (int x = 0; x < 4; ++x) {
                    if (samples == 1)
                        CHECK_EQ(show(tracer.pixel(x, y)), show(Spectrum(0.1, 0.2, 0.7)));
                    else
                        CHECK_NEAR(tracer.pixel(x, y), Spectrum(0.1, 0.2, 0.7), 1e-15);
                }
        }
    }
    // Without 115 an escaping ray still brings back the ambient intensity.
    const Scene ambient_only = parse_scene(join(kTestViewer, "103 0.3 0.4 0.5\n"));
    CHECK_EQ(show(Tracer(ambient_only, {}).pixel(0, 0)), show(Spectrum(0.3, 0.4, 0.5)));
}

TEST(the_other_render_modes_stay_black_where_nothing_is_hit) {
    const Scene scene = parse_scene(join(kTestViewer, "115 0.1 0.2 0.7\n"));
    for (RenderMode mode : {RenderMode::depth, RenderMode::colour, RenderMode::normal}) {
        RenderOptions options;
        options.mode = mode;
        CHECK_EQ(show(Tracer(scene, options).pixel(1, 2)), show(Spectrum(0.0)));
    }
}

TEST(no_ambient_leaves_the_background_on) {
    // --no-ambient drops the ambient term I_a kd colour; the background is not a light.
    const Scene scene = parse_scene(join(kTestViewer, "103 0.5 0.5 0.5\n115 0.1 0.2 0.7\n"));
    RenderOptions options;
    options.ambient = false;
    CHECK_EQ(show(Tracer(scene, options).pixel(0, 0)), show(Spectrum(0.1, 0.2, 0.7)));
}

TEST(a_mirror_sphere_reflects_the_background_by_hand) {
    // A sphere of radius 1 at the origin, surface colour c, ks 0.6, kd 0.5, under ambient A and
    // background B, no lights. Head on (from z = 5 toward -z) the ray meets the sphere at
    // (0, 0, 1) and reflects straight back, into the empty sky: A kd c + ks B.
    const Spectrum a(0.2, 0.3, 0.4), b(0.1, 0.5, 0.9), c(0.9, 0.6, 0.3);
    const double ks = 0.6, kd = 0.5;
    const Scene scene =
        parse_scene(join(kTestViewer, object_text(103, {a[0], a[1], a[2]}), "\n",
                         object_text(115, {b[0], b[1], b[2]}), "\n1 1 0 0 0 ",
                         object_text(100, {c[0], c[1], c[2], ks, 20, kd, 0, 1}), "\n"));
    const Ray ray{{0, 0, 5}, {0, 0, -1}};
    CHECK_NEAR(Tracer(scene, {}).trace(ray), a * c * kd + b * ks, 1e-15);
    // Without the ambient light only the mirror term is left.
    const Scene dark =
        parse_scene(join(kTestViewer, object_text(115, {b[0], b[1], b[2]}), "\n1 1 0 0 0 ",
                         object_text(100, {c[0], c[1], c[2], ks, 20, kd, 0, 1})));
    CHECK_NEAR(Tracer(dark, {}).trace(ray), b * ks, 1e-15);
    // -d 0 traces no reflected ray: the local term only.
    RenderOptions shallow;
    shallow.max_depth = 0;
    CHECK_NEAR(Tracer(scene, shallow).trace(ray), a * c * kd, 1e-15);
}

TEST(refraction_brings_the_background_back_unattenuated) {
    // Clear glass (kd 0, ks 0, ior 1.5, strong absorption) fills the half-space z < 0; the
    // background is B and there is no other light. The reflected ray escapes into the sky
    // and the refracted ray travels inside the glass for ever: neither hits anything, so both
    // bring back B, unattenuated, and the value is F B + (1 - F) B = B at every angle.
    const Spectrum b(0.1, 0.5, 0.9);
    const Scene scene =
        parse_scene(join(kTestViewer, object_text(115, {b[0], b[1], b[2]}), "\n2 0  0 0 1 ",
                         object_text(114, {1, 1, 1, 0, 1, 0, 1.5, 0.5, 2, 40})));
    Tracer tracer(scene, exhaustive());
    for (double theta : {0.0, 0.3, 0.9, 1.4}) {
        const Vec3 d{std::sin(theta), 0, -std::cos(theta)};
        CHECK_NEAR(tracer.trace({-3 * d, d}), b, 1e-12);
    }
    // A slab z in [-1, 0] with that absorption a, head on: the last segment, out of the slab's
    // far side into the sky, brings back B without decay; only the crossing decays. With no
    // reflection, the one path in and out carries (1 - F)^2 e^{-a} B.
    const Spectrum a(0.5, 2, 4);
    const Scene slab =
        parse_scene(join(kTestViewer, object_text(115, {b[0], b[1], b[2]}), "\n12 -9 -9 -1 9 9 0 ",
                         object_text(114, {1, 1, 1, 0, 1, 0, 1.5, a[0], a[1], a[2]})));
    RenderOptions no_mirror;
    no_mirror.reflection = false;
    const double f = fresnel_reflectance(1, 1, 1.5);
    Spectrum expected;
    for (std::size_t i = 0; i < kSpectrumComponents; ++i)
        expected[i] = (1 - f) * (1 - f) * std::exp(-a[i]) * b[i];
    CHECK_NEAR(Tracer(slab, no_mirror).trace({{0, 0, 5}, {0, 0, -1}}), expected, 1e-14);
}

TEST(background_errors_name_their_place) {
    CHECK_EQ(scene_error(join(kTestViewer, "115 0 0 0\n115 1 1 1\n")),
             std::string("test.in:3:1: a second background (115); a scene has at most one, the "
                         "first is at 2:1"));
    CHECK_EQ(scene_error(join(kTestViewer, "115 0 0\n")),
             std::string("test.in:2:8: unexpected end of file: expected background colour"));
    CHECK_EQ(scene_error(join(kTestViewer, "115 0 x 0\n")),
             std::string("test.in:2:7: expected background colour (a number), got 'x'"));
    CHECK_EQ(scene_error(join(kTestViewer, "115 0 1e999 0\n")),
             std::string("test.in:2:7: background colour must be a finite number, got '1e999'"));
    // 115 is a top-level object, not a surface.
    CHECK_CONTAINS(scene_error(join(kTestViewer, "1 1 0 0 0 115 1 1 1\n")),
                   "test.in:2:11: expected a surface ID (one of");
    CHECK_CONTAINS(scene_error(join(kTestViewer, "1 1 0 0 0 115 1 1 1\n")), "got 115 (background)");
}

TEST(read_only_summary_mentions_the_background) {
    const std::filesystem::path dir = work_dir("background_summary");
    write_file(dir / "sky.in", join(kTestViewer, "115 0.25 0.5 1\n"));
    const RunResult r = run_rt(dir, "-r sky.in");
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.out, std::string("sky.in: 0 objects, 0 lights, background 0.25 0.5 1, 4x4\n"));
}
