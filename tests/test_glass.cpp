// The glass surface (114) against closed forms: the Fresnel reflectance at known angles and
// against its textbook sine and tangent forms, the split of a ray into F and 1 - F, Beer's law
// through slabs and a sphere worked out by hand (with the internal reflections and the
// recursion limits), and every reader error.
#include <cmath>
#include <numbers>
#include <string>

#include "rt/optics.h"
#include "rt/trace.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

// F written independently of fresnel_reflectance, with the angles themselves (the
// sin/tan forms of the Fresnel equations): valid for 0 < theta_i < pi/2 below the critical
// angle.
double fresnel_by_angles(double theta_i, double n1, double n2) {
    const double theta_t = std::asin(n1 * std::sin(theta_i) / n2);
    const double rs = std::pow(std::sin(theta_i - theta_t) / std::sin(theta_i + theta_t), 2);
    const double rp = std::pow(std::tan(theta_i - theta_t) / std::tan(theta_i + theta_t), 2);
    return (rs + rp) / 2;
}

double normal_reflectance(double n1, double n2) { return std::pow((n1 - n2) / (n1 + n2), 2); }

double degrees(double d) { return d * std::numbers::pi / 180; }

// A glass surface with the given ior and absorption and no local terms of its own (kd 0,
// ks 0), so that what a ray brings back comes only through the mirror and the refraction.
std::string clear_glass(double ior, const Spectrum& absorption) {
    return object_text(114, {1, 1, 1, 0, 1, 0, ior, absorption[0], absorption[1], absorption[2]});
}

std::string surface_error(const std::string& surface) {
    return scene_error(join(kTestViewer, "1 1 0 0 0 ", surface));
}

Spectrum exp_of(const Spectrum& s, double scale) {
    return {std::exp(scale * s[0]), std::exp(scale * s[1]), std::exp(scale * s[2])};
}

}  // namespace

// ---------------------------------------------------------------- the Fresnel reflectance

TEST(fresnel_at_normal_incidence) {
    for (const double n : {1.0, 1.33, 1.5, 2.42, 0.7}) {
        const double expected = std::pow((n - 1) / (n + 1), 2);
        CHECK_NEAR(fresnel_reflectance(1, 1, n), expected, 1e-15);
        CHECK_NEAR(fresnel_reflectance(1, n, 1), expected, 1e-15);  // the same leaving
    }
    CHECK_NEAR(fresnel_reflectance(1, 1, 1.5), 0.04, 1e-16);
    // The same index on both sides: no boundary, nothing reflected, at any angle.
    for (const double c : {1.0, 0.7, 0.2, 1e-3})
        CHECK_NEAR(fresnel_reflectance(c, 1.5, 1.5), 0, 1e-20);
}

TEST(fresnel_at_the_critical_angle_and_beyond) {
    // From glass (1.5) into air, sin(theta_c) = 1 / 1.5.
    const double theta_c = std::asin(1 / 1.5);
    CHECK(fresnel_reflectance(std::cos(theta_c), 1.5, 1) > 1 - 1e-6);
    // Just below, F is less than 1 and still the formula's; it climbs steeply toward 1.
    double previous = 0;
    for (const double below : {1e-2, 1e-3, 1e-4, 1e-5}) {
        const double theta = theta_c - below;
        const double f = fresnel_reflectance(std::cos(theta), 1.5, 1);
        CHECK(f < 1);
        CHECK(f > previous);
        CHECK_NEAR(f, fresnel_by_angles(theta, 1.5, 1), 1e-9);
        previous = f;
    }
    CHECK(previous > 0.95);
    // Beyond it, total internal reflection: exactly 1.
    for (const double theta : {theta_c + 1e-9, theta_c + 1e-3, degrees(60), degrees(89.9)})
        CHECK_EQ(fresnel_reflectance(std::cos(theta), 1.5, 1), 1.0);
    // Entering a denser medium there is no critical angle.
    CHECK(fresnel_reflectance(std::cos(degrees(60)), 1, 1.5) < 0.1);
}

TEST(fresnel_at_grazing_incidence) {
    CHECK_EQ(fresnel_reflectance(0, 1, 1.5), 1.0);
    CHECK_EQ(fresnel_reflectance(0, 1.5, 1), 1.0);
    // Approaching grazing, F tends to 1 from below.
    CHECK(fresnel_reflectance(1e-3, 1, 1.5) > 0.99);
    CHECK(fresnel_reflectance(1e-3, 1, 1.5) < 1);
    CHECK_NEAR(fresnel_reflectance(std::cos(degrees(89)), 1, 1.5),
               fresnel_by_angles(degrees(89), 1, 1.5), 1e-12);
}

TEST(fresnel_at_brewsters_angle) {
    // At tan(theta_B) = n2 / n1, R_p = 0 and the refracted ray is perpendicular to the
    // reflected one, so R_s = sin^2(theta_i - theta_t) = cos^2(2 theta_B): F = cos^2(2 theta_B)
    // / 2.
    for (const auto& [n1, n2] : {std::pair{1.0, 1.5}, {1.5, 1.0}, {1.0, 2.42}, {1.33, 1.0}}) {
        const double theta_b = std::atan(n2 / n1);
        CHECK_NEAR(fresnel_reflectance(std::cos(theta_b), n1, n2),
                   std::pow(std::cos(2 * theta_b), 2) / 2, 1e-15);
    }
}

TEST(fresnel_is_the_same_both_ways_through_a_boundary) {
    // Light crossing a boundary one way at theta_i and back the other way at theta_t is
    // reflected alike (Stokes' relations).
    Random random(114);
    for (int i = 0; i < 2000; ++i) {
        const double n1 = random.uniform(1, 2.5), n2 = random.uniform(1, 2.5);
        const double theta_i = random.uniform(0, std::numbers::pi / 2);
        const double sin_t = n1 * std::sin(theta_i) / n2;
        if (sin_t >= 1) continue;
        const double theta_t = std::asin(sin_t);
        CHECK_NEAR(fresnel_reflectance(std::cos(theta_i), n1, n2),
                   fresnel_reflectance(std::cos(theta_t), n2, n1), 1e-12);
    }
}

TEST(fresnel_against_the_angle_forms_at_random_angles) {
    Random random(1140);
    int checked = 0, total_internal = 0;
    for (int i = 0; i < 20000; ++i) {
        const double n1 = random.uniform(1, 2.5), n2 = random.uniform(1, 2.5);
        const double theta = random.uniform(0.01, std::numbers::pi / 2 - 0.01);
        const double f = fresnel_reflectance(std::cos(theta), n1, n2);
        const double sin_t = n1 * std::sin(theta) / n2;
        if (sin_t > 1) {
            CHECK_EQ(f, 1.0);
            ++total_internal;
            continue;
        }
        if (sin_t > 1 - 1e-6 || std::fabs(n1 - n2) < 1e-6) continue;  // ill-conditioned forms
        CHECK(f >= 0 && f <= 1);
        CHECK_NEAR(f, fresnel_by_angles(theta, n1, n2), 1e-9);
        ++checked;
    }
    CHECK(checked > 10000);
    CHECK(total_internal > 1000);
}

// ---------------------------------------------------------------- the tracer

TEST(reflected_and_refracted_weights_add_up_to_one) {
    // The half-space z < 0 of glass, everything else empty under ambient 1: the reflected ray
    // and the refracted ray both escape and bring back 1, so the value is F + (1 - F) = 1 at
    // every angle, with or without absorption (an escaping ray is not attenuated). Entering
    // from inside (index 1.5 carried by the ray) the same holds, total internal reflection
    // included.
    Random random(11400);
    for (const Spectrum absorption : {Spectrum(0.0), Spectrum(0.5, 2.0, 40.0)}) {
        const Scene scene =
            parse_scene(join(kTestViewer, "103 1 1 1\n2 0  0 0 1 ", clear_glass(1.5, absorption)));
        Tracer tracer(scene, exhaustive());
        for (int i = 0; i < 200; ++i) {
            Vec3 d = random.unit_vector();
            if (std::fabs(d.z) < 1e-3) continue;
            const Vec3 origin = -3 * d;  // every ray meets the plane at the origin
            const bool inside = d.z > 0;
            const Spectrum v = tracer.trace({origin, d}, 0, 1, inside ? 1.5 : 1,
                                            inside ? absorption : Spectrum(0.0));
            // From inside, the first leg (3 units) is absorbed.
            const Spectrum expected = inside ? exp_of(absorption, -3) : Spectrum(1.0);
            CHECK_NEAR(v, expected, 1e-12);
        }
    }
}

TEST(glass_half_space_at_an_angle_by_hand) {
    // Glass (1.5, absorption a) fills z < 0 down to a grey floor at z = -2 lit by ambient
    // 0.5 only. A ray meets the glass at the origin at 50 degrees: F of it comes back from the
    // empty sky (0.5); 1 - F refracts to theta_t, crosses 2 / cos(theta_t) of glass and sees the
    // floor (0.5 x kd 0.8 x colour), which it brings back attenuated.
    const Spectrum a(0.3, 0.1, 0.05), colour(0.9, 0.6, 0.3);
    const Scene scene =
        parse_scene(join(kTestViewer, "103 0.5 0.5 0.5\n2 0  0 0 1 ", clear_glass(1.5, a),
                         "\n2 -2  0 0 1  100 0.9 0.6 0.3 0 1 0.8 0 1\n"));
    const double theta = degrees(50);
    const Vec3 d{std::sin(theta), 0, -std::cos(theta)};
    const double f = fresnel_by_angles(theta, 1, 1.5);
    const double theta_t = std::asin(std::sin(theta) / 1.5);
    const Spectrum floor = colour * (0.5 * 0.8);
    const Spectrum expected =
        Spectrum(0.5 * f) + floor * exp_of(a, -2 / std::cos(theta_t)) * (1 - f);
    CHECK_NEAR(Tracer(scene, {}).trace({-4 * d, d}), expected, 1e-12);
}

TEST(beers_law_through_a_slab_by_hand) {
    // A slab of glass (a box, z from -d to 0, wide in x and y) in front of a floor at z = -5
    // (colour c, kd 1) under ambient A; the glass has kd 0. Head on, every boundary reflects
    // F = ((n - 1)/(n + 1))^2. With e = exp(-a d), a ray going down inside brings back
    // D = e ((1 - F) A c + F U) and one going up U = e ((1 - F) A + F D), so
    //   D = e (1 - F) (A c + e F A) / (1 - e^2 F^2),  pixel = F A + (1 - F) D.
    const double n = 1.5, f = normal_reflectance(1, n);
    const Spectrum a(0.1, 0.5, 2.0), c(0.9, 0.6, 0.3), ambient(1.0, 0.8, 0.6);
    for (const double thickness : {1.0, 0.25, 2.0}) {
        const Scene scene =
            parse_scene(join(kTestViewer, object_text(103, {ambient[0], ambient[1], ambient[2]}),
                             "\n", object_text(12, {-100, -100, -thickness, 100, 100, 0}), " ",
                             clear_glass(n, a), "\n2 -5  0 0 1  100 0.9 0.6 0.3 0 1 1 0 1\n"));
        const Spectrum e = exp_of(a, -thickness);
        const Ray ray{{0.1, 0.2, 5}, {0, 0, -1}};
        Spectrum down;
        for (std::size_t i = 0; i < kSpectrumComponents; ++i)
            down[i] = e[i] * (1 - f) * (ambient[i] * c[i] + e[i] * f * ambient[i]) /
                      (1 - e[i] * e[i] * f * f);
        CHECK_NEAR(Tracer(scene, exhaustive()).trace(ray), ambient * f + down * (1 - f), 1e-12);

        // With the default cut-offs (-d 7, -w 0.01) the second internal reflection weighs
        // (1 - F) F^2 = 0.0015 and is not traced: only one internal reflection comes back,
        // and the series stops: D = e (1 - F) (A c + e F A).
        Spectrum truncated;
        for (std::size_t i = 0; i < kSpectrumComponents; ++i)
            truncated[i] = e[i] * (1 - f) * (ambient[i] * c[i] + e[i] * f * ambient[i]);
        CHECK_NEAR(Tracer(scene, {}).trace(ray), ambient * f + truncated * (1 - f), 1e-12);
    }
}

TEST(glass_sphere_centre_pixel_by_hand) {
    // A glass sphere (radius 1, n 1.5, kd 0.1, ks 0.5, colour g, absorption a) in front of a
    // floor at z = -5 (colour c, kd 1), ambient A, and a directional light I shining along -z.
    // The centre pixel's ray meets every boundary head on (F = 0.04) and runs 2 units inside.
    // At the front, outside: the local terms L_front = A kd g + I (kd g + ks) (d.s = r.s = 1).
    // Inside, the light is behind the surface (back) or blocked by the sphere (front), so the
    // local term is only L = A kd g. The floor is in the sphere's shadow: it shows A c.
    // With e = exp(-2a):  D = e (L + (1 - F) A c + F U),  U = e (L + (1 - F) A + F D), and
    // the pixel is L_front + F A + (1 - F) D.
    const double f = 0.04, kd = 0.1, ks = 0.5;
    const Spectrum g(0.2, 0.4, 0.8), a(0.05, 0.2, 0.6), c(0.9, 0.6, 0.3), ambient(0.3);
    const Spectrum light(2.0);
    const std::string scene_text = join(
        "102  0 0 5  0 0 0  1 0 0  0 1 0  2 2\n", "103 0.3 0.3 0.3\n", "113  0 0 -1  2 2 2\n",
        "1 1  0 0 0  ", object_text(114, {g[0], g[1], g[2], ks, 20, kd, 1.5, a[0], a[1], a[2]}),
        "\n2 -5  0 0 1  100 0.9 0.6 0.3 0 1 1 0 1\n");
    const Scene scene = parse_scene(scene_text);
    const Spectrum e = exp_of(a, -2);
    Spectrum down;
    for (std::size_t i = 0; i < kSpectrumComponents; ++i) {
        const double l = ambient[i] * kd * g[i];
        const double d_free = e[i] * (l + (1 - f) * ambient[i] * c[i]);
        const double u_free = e[i] * (l + (1 - f) * ambient[i]);
        down[i] = (d_free + e[i] * f * u_free) / (1 - e[i] * e[i] * f * f);
    }
    const Spectrum front = ambient * g * kd + light * (g * kd + Spectrum(ks));
    CHECK_NEAR(Tracer(scene, exhaustive()).pixel(1, 1), front + ambient * f + down * (1 - f),
               1e-12);
    // The colour mode shows the glass's colour.
    RenderOptions colour_mode;
    colour_mode.mode = RenderMode::colour;
    CHECK_NEAR(Tracer(scene, colour_mode).pixel(1, 1), g, 0);
}

TEST(total_internal_reflection_inside_a_glass_sphere) {
    // From inside a glass sphere (n 1.5) a ray meeting the surface at theta keeps meeting it at
    // theta, along chords of 2 cos(theta). Below the critical angle each hit lets 1 - F out (to
    // ambient 1) and reflects F; a hit at depth k sends out a ray of depth k + 1, traced only
    // while k + 1 <= -d. From a start at cos(theta) from the first hit, the value is
    //   sum over k = 0 .. d-1 of exp(-a (cos + 2 k cos)) F^k (1 - F).
    // Beyond it F = 1: nothing ever leaves.
    const double a = 0.3;
    const Scene scene =
        parse_scene(join(kTestViewer, "103 1 1 1\n1 1  0 0 0  ", clear_glass(1.5, Spectrum(a))));
    for (const int depth : {1, 3, 7}) {
        RenderOptions options;
        options.min_weight = 0;
        options.max_depth = depth;
        Tracer tracer(scene, options);
        const auto from_inside = [&](double theta) {
            return tracer.trace({{0, std::sin(theta), 0}, {1, 0, 0}}, 0, 1, 1.5, Spectrum(a))[0];
        };
        const double theta = degrees(30), cos = std::cos(theta);
        const double f = fresnel_reflectance(cos, 1.5, 1);
        CHECK_NEAR(f, fresnel_by_angles(theta, 1.5, 1), 1e-12);
        double expected = 0;
        for (int k = 0; k < depth; ++k)
            expected += std::exp(-a * (cos + 2 * k * cos)) * std::pow(f, k) * (1 - f);
        CHECK_NEAR(from_inside(theta), expected, 1e-12);
        CHECK_NEAR(from_inside(degrees(60)), 0, 0);
    }
}

TEST(cut_offs_apply_to_the_fresnel_weights) {
    // Head on at the glass half-space z < 0 under ambient 1: F = 0.04 reflected, 0.96
    // refracted, each escaping to bring back 1.
    const Scene scene =
        parse_scene(join(kTestViewer, "103 1 1 1\n2 0  0 0 1 ", clear_glass(1.5, Spectrum(0.0))));
    const Ray ray{{0, 0, 5}, {0, 0, -1}};
    const auto value = [&](double min_weight, int max_depth = 7) {
        RenderOptions options;
        options.min_weight = min_weight;
        options.max_depth = max_depth;
        return Tracer(scene, options).trace(ray)[0];
    };
    CHECK_NEAR(value(0.039), 1, 1e-15);
    CHECK_NEAR(value(0.041), 0.96, 1e-15);  // the reflected ray weighs F < the cut-off
    CHECK_NEAR(value(0.961), 0, 0);         // and the refracted ray 1 - F
    CHECK_NEAR(value(0.0, 0), 0, 0);        // no secondary rays at all
    // The switches remove their rays.
    RenderOptions options;
    options.reflection = false;
    CHECK_NEAR(Tracer(scene, options).trace(ray)[0], 0.96, 1e-15);
    options = {};
    options.refraction = false;
    CHECK_NEAR(Tracer(scene, options).trace(ray)[0], 0.04, 1e-15);
}

TEST(glass_blocks_shadow_rays) {
    // As every object does: a floor under a glass sphere, lit from straight above.
    const Scene scene =
        parse_scene(join(kTestViewer, "113 0 -1 0  1 1 1\n", "1 1  0 3 0  ",
                         clear_glass(1.5, Spectrum(0.0)), "\n2 0  0 1 0  100 1 1 1 0 1 1 0 1\n"));
    Tracer tracer(scene, {});
    CHECK_NEAR(tracer.trace({{0, 1, 0.5}, {0, -1, 0}}), Spectrum(0.0), 0);
    CHECK_NEAR(tracer.trace({{3, 1, 0.5}, {0, -1, 0}}), Spectrum(1.0), 1e-15);
}

TEST(glass_inside_other_surfaces) {
    // A checker of glass and a simple surface: each cell behaves as its own surface.
    const Scene scene =
        parse_scene(join(kTestViewer, "103 1 1 1\n2 0  0 0 1  107 1  ",
                         clear_glass(1.5, Spectrum(0.0)), "  100 0 0 0 0 1 0 0 1\n"));
    Tracer tracer(scene, exhaustive());
    CHECK_NEAR(tracer.trace({{0.5, 0.5, 5}, {0, 0, -1}}), Spectrum(1.0), 1e-15);  // glass
    CHECK_NEAR(tracer.trace({{1.5, 0.5, 5}, {0, 0, -1}}), Spectrum(0.0), 0);      // black
}

// ---------------------------------------------------------------- reading

TEST(glass_reads_its_ten_numbers) {
    const Scene scene =
        parse_scene(join(kTestViewer, "1 1 0 0 0  114 0.1 0.2 0.3  0.4 50 0.6 1.7  0 0.5 2"));
    const Material m = scene.objects.at(0).surface->at({0, 0, 1});
    CHECK_NEAR(m.colour, Spectrum(0.1, 0.2, 0.3), 0);
    CHECK_EQ(m.ks, 0.4);
    CHECK_EQ(m.ke, 50.0);
    CHECK_EQ(m.kd, 0.6);
    CHECK_EQ(m.ior, 1.7);
    CHECK_NEAR(m.absorption, Spectrum(0.0, 0.5, 2.0), 0);
    CHECK(m.fresnel);
    CHECK_EQ(m.kt, 0.0);
    // The simple surface is no dielectric.
    CHECK(!parse_scene(join(kTestViewer, "1 1 0 0 0  100 1 1 1 0 1 1 0.5 1.5"))
               .objects.at(0)
               .surface->at({0, 0, 1})
               .fresnel);
}

TEST(glass_read_errors) {
    // "1 1 0 0 0 " takes columns 1-10, so the surface starts at 11: 114 at 11, colour at 15,
    // ks 21, ke 23, kd 25, ior 27 and, after an ior of 1.5, absorption at 31.
    CHECK_CONTAINS(surface_error("114 1 1 1 0 1 1 0 0 0 0"),
                   "test.in:2:27: glass ior (refractive index) must be > 0, got 0");
    CHECK_CONTAINS(surface_error("114 1 1 1 0 1 1 -1.5 0 0 0"),
                   "test.in:2:27: glass ior (refractive index) must be > 0, got -1.5");
    CHECK_CONTAINS(surface_error("114 1 1 1 0 1 1 1.5 0 -1 0"),
                   "test.in:2:31: glass absorption components must be >= 0");
    CHECK_CONTAINS(surface_error("114 1 1 1 0 1 1 1.5 -1 0 0"),
                   "test.in:2:31: glass absorption components must be >= 0");
    CHECK_CONTAINS(surface_error("114 1 -1 1 0 1 1 1.5 0 0 0"),
                   "test.in:2:15: surface colour components must be >= 0");
    CHECK_CONTAINS(surface_error("114 1 1 1 -1 1 1 1.5 0 0 0"),
                   "test.in:2:21: surface ks (specular coefficient) must be >= 0, got -1");
    CHECK_CONTAINS(surface_error("114 1 1 1 0 -1 1 1.5 0 0 0"),
                   "test.in:2:23: surface ke (specular exponent) must be >= 0, got -1");
    CHECK_CONTAINS(surface_error("114 1 1 1 0 1 -1 1.5 0 0 0"),
                   "test.in:2:25: surface kd (diffuse coefficient) must be >= 0, got -1");
    CHECK_CONTAINS(surface_error("114 1 1 1 0 1 1 x 0 0 0"),
                   "test.in:2:27: expected glass ior (refractive index) (a number), got 'x'");
    CHECK_CONTAINS(surface_error("114 1 1 1 0 1 1 1.5 0 0"),
                   "unexpected end of file: expected glass absorption");
    CHECK_CONTAINS(surface_error("114 1 1 1 0 1 1 1.5 0 inf 0"),
                   "test.in:2:33: glass absorption must be a finite number, got 'inf'");
    // Zero absorption and an index below 1 are allowed.
    CHECK_EQ(surface_error("114 1 1 1 0 1 1 0.5 0 0 0"), std::string());
    // A glass surface at the top level, as any surface, is an error.
    CHECK_CONTAINS(scene_error(join(kTestViewer, "114 1 1 1 0 1 1 1.5 0 0 0")),
                   "test.in:2:1: surface 114 (glass surface) found where an object is expected");
}
