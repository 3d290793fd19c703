// Lights: point lights (101, 104), the spot light (109), the sphere light (110) and the
// directional light (113), sampled at known points and checked against values worked out by
// hand or by closed forms computed here, not by the lights' own code.
#include <cmath>
#include <numbers>
#include <thread>
#include <vector>

#include "rt/render.h"
#include "rt/trace.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

// The one light of a scene made of the test viewer and `light_text`.
Light read_light(const std::string& light_text) {
    const Scene scene = parse_scene(join(kTestViewer, light_text));
    CHECK_EQ(scene.lights.size(), std::size_t{1});
    return scene.lights.at(0);
}

// The error that reading `light_text` (on line 2, after the test viewer) raises.
std::string light_error(const std::string& light_text) {
    return scene_error(join(kTestViewer, light_text));
}

bool same_bits(const LightSample& a, const LightSample& b) {
    return a.direction == b.direction && a.distance == b.distance && a.intensity == b.intensity;
}

// The mean of 1 / |x - p|^2 over the points p of a sphere of radius r whose centre is at
// distance d from x: integrating over the height on the sphere (areas are uniform in it) gives
// (1 / 2dr) ln((d + r) / |d - r|), for points inside and outside alike.
double mean_inverse_square(double d, double r) {
    return std::log((d + r) / std::fabs(d - r)) / (2 * d * r);
}

// The fraction of a sphere light (radius r, centre at distance d from a point) that the point
// sees past a blocking sphere of radius b whose centre lies on the line to the light's centre
// at distance D, the blocker lying wholly between the point and the light. The blocker hides
// the directions within the angle a of that line, sin a = b / D. On the light, measure the
// angle theta from the point nearest to x: a light point is hidden when
// r sin(theta) <= tan(a) (d - r cos(theta)), that is sin(theta + a) <= k with k = d sin(a) / r,
// which holds on a cap near x (theta <= asin k - a) and a cap on the far side
// (theta >= pi - asin k - a). Their areas sum to 1 - cos(asin k) cos(a) of the sphere.
double unblocked_fraction(double d, double r, double D, double b) {
    const double sin_a = b / D;
    const double k = d * sin_a / r;
    if (k >= 1) return 0;
    return std::sqrt(1 - k * k) * std::sqrt(1 - sin_a * sin_a);
}

}  // namespace

// ---------------------------------------------------------------- point lights (101, 104)

TEST(point_light_at_known_points) {
    const Light with = read_light("101  1 2 3  4 8 12");
    const Light without = read_light("104  1 2 3  4 8 12");
    CHECK_EQ(with.sample_count(), 1);
    CHECK_EQ(without.sample_count(), 1);
    // Four units straight below along z.
    LightSample s = with.sample({1, 2, -1}, 0);
    CHECK_NEAR(s.direction, Vec3(0, 0, 1), 1e-15);
    CHECK_NEAR(s.distance, 4, 1e-15);
    CHECK_NEAR(s.intensity, Spectrum(0.25, 0.5, 0.75), 1e-15);
    s = without.sample({1, 2, -1}, 0);
    CHECK_NEAR(s.distance, 4, 1e-15);
    CHECK_NEAR(s.intensity, Spectrum(4, 8, 12), 1e-15);
    // A 3-4-5 triangle: (1, 2, 3) seen from (4, 6, 3).
    s = with.sample({4, 6, 3}, 0);
    CHECK_NEAR(s.direction, Vec3(-0.6, -0.8, 0), 1e-15);
    CHECK_NEAR(s.distance, 5, 1e-14);
    CHECK_NEAR(s.intensity, Spectrum(4.0 / 25, 8.0 / 25, 12.0 / 25), 1e-15);
}

TEST(point_light_random_points) {
    Random random(101);
    for (int i = 0; i < 2000; ++i) {
        const Vec3 position = random.in_box(10);
        const Vec3 x = random.in_box(10);
        const Vec3 colour{random.uniform(0, 5), random.uniform(0, 5), random.uniform(0, 5)};
        const bool falloff = i % 2 == 0;
        const Light light =
            read_light(object_text(falloff ? 101 : 104, {position.x, position.y, position.z,
                                                         colour.x, colour.y, colour.z}));
        const LightSample s = light.sample(x, 0);
        // The tracer samples a point light inline from its parameters (Light::point): the
        // same sample to the bit.
        CHECK(light.point() != nullptr);
        CHECK(light.point()->position == position && light.point()->falloff == falloff);
        CHECK(same_bits(sample_point_light(*light.point(), x), s));
        const double dx = position.x - x.x, dy = position.y - x.y, dz = position.z - x.z;
        const double distance = std::hypot(dx, dy, dz);
        CHECK_NEAR(s.distance, distance, 1e-12 * (1 + distance));
        CHECK_NEAR(s.direction, Vec3(dx / distance, dy / distance, dz / distance), 1e-12);
        const double scale = falloff ? 1 / (distance * distance) : 1.0;
        CHECK_NEAR(s.intensity, Spectrum(colour.x * scale, colour.y * scale, colour.z * scale),
                   1e-12 * (1 + 5 * scale));
    }
}

TEST(only_point_lights_give_their_parameters) {
    for (const LightType& type : light_types())
        CHECK_EQ(type.point != nullptr, type.id == 101 || type.id == 104);
}

TEST(point_light_at_the_lit_point_gives_nothing) {
    const LightSample s = read_light("101  1 2 3  4 8 12").sample({1, 2, 3}, 0);
    CHECK(s.intensity.is_black());
    CHECK(std::isfinite(s.direction.x) && std::isfinite(s.direction.y) &&
          std::isfinite(s.direction.z));
}

// ---------------------------------------------------------------- spot light (109)

TEST(spot_light_at_known_points) {
    // At (0, 4, 0), pointing down (the direction need not be unit), cut-off 60 degrees,
    // exponent 2, intensity 8.
    const Light spot = read_light("109  0 4 0  0 -2 0  0.5  2  8 8 8");
    CHECK_EQ(spot.sample_count(), 1);
    // On the axis, 4 below: cos = 1, so 8 / 16.
    LightSample s = spot.sample({0, 0, 0}, 0);
    CHECK_NEAR(s.direction, Vec3(0, 1, 0), 1e-15);
    CHECK_NEAR(s.distance, 4, 1e-15);
    CHECK_NEAR(s.intensity, Spectrum(0.5), 1e-15);
    // A 3-4-5 triangle: cos = 4/5, so 8 * 0.64 / 25.
    s = spot.sample({3, 0, 0}, 0);
    CHECK_NEAR(s.direction, Vec3(-0.6, 0.8, 0), 1e-15);
    CHECK_NEAR(s.distance, 5, 1e-14);
    CHECK_NEAR(s.intensity, Spectrum(8 * 0.64 / 25), 1e-15);
    // The same angle on the other side and behind the axis.
    s = spot.sample({0, 0, -3}, 0);
    CHECK_NEAR(s.intensity, Spectrum(8 * 0.64 / 25), 1e-15);
    // cos = 4 / sqrt(116) < 0.5: outside the cone. Direction and distance are still reported.
    s = spot.sample({10, 0, 0}, 0);
    CHECK(s.intensity.is_black());
    CHECK_NEAR(s.distance, std::sqrt(116.0), 1e-13);
    CHECK_NEAR(s.direction, Vec3(-10, 4, 0) / std::sqrt(116.0), 1e-15);
    // Above the light, straight against its direction: cos = -1.
    CHECK(spot.sample({0, 9, 0}, 0).intensity.is_black());
}

TEST(spot_light_random_points) {
    Random random(109);
    int lit = 0, dark = 0;
    for (int i = 0; i < 3000; ++i) {
        const Vec3 position = random.in_box(5);
        const Vec3 direction = random.in_box(3);
        if (length(direction) < 0.1) continue;
        const double cos_cutoff = random.uniform(-1, 1);
        const double exponent = random.uniform(0, 20);
        const Light spot =
            read_light(object_text(109, {position.x, position.y, position.z, direction.x,
                                         direction.y, direction.z, cos_cutoff, exponent, 2, 3, 4}));
        const Vec3 x = random.in_box(10);
        const LightSample s = spot.sample(x, 0);
        // The angle at the light between its axis and the way to x, found with atan2.
        const Vec3 from_light = x - position;
        const double angle =
            std::atan2(length(cross(from_light, direction)), dot(from_light, direction));
        const double cos_angle = std::cos(angle);
        const double distance = length(from_light);
        CHECK_NEAR(s.distance, distance, 1e-12 * (1 + distance));
        CHECK_NEAR(s.direction, -from_light / distance, 1e-12);
        // Near the cut-off the two ways of computing the angle may disagree on which side
        // of it x lies; skip those points.
        if (std::fabs(cos_angle - cos_cutoff) < 1e-9) continue;
        if (cos_angle < cos_cutoff) {
            ++dark;
            CHECK(s.intensity.is_black());
        } else {
            ++lit;
            const double expected =
                std::pow(std::max(cos_angle, 0.0), exponent) / (distance * distance);
            CHECK_NEAR(s.intensity, Spectrum(2 * expected, 3 * expected, 4 * expected),
                       1e-9 * (1 + 4 * expected));
        }
    }
    CHECK(lit > 500);
    CHECK(dark > 500);
}

TEST(spot_light_cut_off_edge) {
    // cos cut-off 0 (a half-space) with exponent 0: a point exactly level with the light is
    // at the edge, and the edge is lit, at full strength since 0^0 = 1.
    const Light flat = read_light("109  0 0 0  0 -1 0  0  0  1 1 1");
    CHECK_NEAR(flat.sample({2, 0, 0}, 0).intensity, Spectrum(0.25), 1e-15);
    CHECK(flat.sample({2, 1e-9, 0}, 0).intensity.is_black());
    CHECK_NEAR(flat.sample({2, -1e-9, 0}, 0).intensity, Spectrum(0.25), 1e-12);
    // cos cut-off 1: a zero-width beam lights only points exactly on its axis.
    const Light beam = read_light("109  0 0 0  0 -1 0  1  5  1 1 1");
    CHECK_NEAR(beam.sample({0, -2, 0}, 0).intensity, Spectrum(0.25), 1e-15);
    CHECK(beam.sample({1e-6, -2, 0}, 0).intensity.is_black());
    // cos cut-off 0.8 at distance 5: points just inside and just outside the 3-4-5 angle.
    const Light spot = read_light("109  0 0 0  0 -1 0  0.8  0  25 25 25");
    CHECK_NEAR(spot.sample({3 - 1e-7, -4, 0}, 0).intensity, Spectrum(1), 1e-7);
    CHECK(spot.sample({3 + 1e-7, -4, 0}, 0).intensity.is_black());
}

TEST(spot_light_exponent) {
    // At the 3-4-5 angle (cos 0.8) and 5 away, the light is 0.8^exponent of what a point light
    // of the same intensity gives there; on the axis it is the point light's.
    for (const double exponent : {0.0, 0.5, 1.0, 2.0, 7.5, 50.0}) {
        const Light spot =
            read_light(object_text(109, {0, 0, 0, 0, -1, 0, 0.1, exponent, 25, 50, 75}));
        const double spread = std::pow(0.8, exponent);
        CHECK_NEAR(spot.sample({3, -4, 0}, 0).intensity, Spectrum(spread, 2 * spread, 3 * spread),
                   1e-13);
        CHECK_NEAR(spot.sample({0, -5, 0}, 0).intensity, Spectrum(1, 2, 3), 1e-13);
    }
}

TEST(spot_light_wider_than_a_half_space) {
    // With cut-off cos -1 the light reaches behind the spot, where the cosine is negative:
    // it counts as 0 there, so exponent 0 still lights the point and any other exponent gives
    // nothing (never a negative or NaN intensity).
    const Light uniform = read_light("109  0 0 0  0 -1 0  -1  0  4 4 4");
    CHECK_NEAR(uniform.sample({0, 2, 0}, 0).intensity, Spectrum(1), 1e-15);
    CHECK_NEAR(uniform.sample({0, -2, 0}, 0).intensity, Spectrum(1), 1e-15);
    for (const double exponent : {0.5, 1.0, 3.0}) {
        const Light spot = read_light(object_text(109, {0, 0, 0, 0, -1, 0, -1, exponent, 4, 4, 4}));
        const LightSample behind = spot.sample({0.5, 2, 0}, 0);
        CHECK(behind.intensity.is_black());
        CHECK(!std::isnan(behind.intensity[0]));
    }
    // A cut-off of 120 degrees (cos -0.5) lights a point 100 degrees off the axis only with
    // exponent 0; a point 130 degrees off is outside.
    const Light wide = read_light("109  0 0 0  0 -1 0  -0.5  0  1 1 1");
    const double off100 = 100 * std::numbers::pi / 180, off130 = 130 * std::numbers::pi / 180;
    CHECK_NEAR(wide.sample({std::sin(off100), -std::cos(off100), 0}, 0).intensity, Spectrum(1),
               1e-12);
    CHECK(wide.sample({std::sin(off130), -std::cos(off130), 0}, 0).intensity.is_black());
}

TEST(spot_light_at_the_lit_point_gives_nothing) {
    const LightSample s = read_light("109  1 2 3  0 -1 0  0.5 1  4 8 12").sample({1, 2, 3}, 0);
    CHECK(s.intensity.is_black());
    CHECK(!std::isnan(s.direction.x));
}

TEST(spot_light_read_errors) {
    // Columns:     1   5     11      19   24 26
    CHECK_CONTAINS(light_error("109 0 4 0  0 0 0  0.5  2  1 1 1"),
                   "test.in:2:12: spot light direction must have a non-zero length");
    CHECK_CONTAINS(light_error("109 0 4 0  0 -1 0  1.5  2  1 1 1"),
                   "test.in:2:20: spot light cos of cut-off angle must be between -1 and 1, "
                   "got 1.5");
    CHECK_CONTAINS(light_error("109 0 4 0  0 -1 0  -1.01  2  1 1 1"),
                   "test.in:2:20: spot light cos of cut-off angle must be between -1 and 1, "
                   "got -1.01");
    CHECK_CONTAINS(light_error("109 0 4 0  0 -1 0  0.5  -1  1 1 1"),
                   "test.in:2:25: spot light exponent must be >= 0, got -1");
    CHECK_CONTAINS(light_error("109 0 4 0  0 -1 0  0.5  2  1 x 1"),
                   "test.in:2:30: expected spot light intensity (a number), got 'x'");
    CHECK_CONTAINS(light_error("109 0 4 0  0 -1 0  0.5  2  1 1"),
                   "test.in:2:31: unexpected end of file: expected spot light intensity");
    CHECK_CONTAINS(light_error("109 0 4 0  0 -1 0  nan  2  1 1 1"),
                   "test.in:2:20: spot light cos of cut-off angle must be a finite number");
    // The extremes are allowed.
    CHECK_EQ(light_error("109 0 4 0  0 -1 0  -1 0  1 1 1"), std::string());
    CHECK_EQ(light_error("109 0 4 0  0 -1 0  1 0  1 1 1"), std::string());
}

// ---------------------------------------------------------------- sphere light (110)

TEST(sphere_light_samples_lie_on_the_sphere) {
    Random random(110);
    for (int trial = 0; trial < 40; ++trial) {
        const int n = 1 + static_cast<int>(random.next() % 300);
        const Vec3 centre = random.in_box(5);
        const double radius = random.uniform(0.05, 2);
        const Light light = read_light(object_text(
            110, {static_cast<double>(n), centre.x, centre.y, centre.z, radius, 3, 6, 9}));
        CHECK_EQ(light.sample_count(), n);
        for (int p = 0; p < 10; ++p) {
            const Vec3 x = random.in_box(8);
            double sum_inverse_square = 0;
            Spectrum sum(0.0);
            for (int i = 0; i < n; ++i) {
                const LightSample s = light.sample(x, i);
                CHECK_NEAR(length(s.direction), 1, 1e-14);
                const Vec3 on_light = x + s.direction * s.distance;
                CHECK_NEAR(length(on_light - centre), radius, 1e-12 * (1 + length(x)));
                // Each sample carries intensity / n with inverse-square falloff.
                const double inverse_square = 1 / length_squared(on_light - x);
                CHECK_NEAR(s.intensity, Spectrum(3, 6, 9) * (inverse_square / n),
                           1e-12 * inverse_square);
                sum_inverse_square += inverse_square;
                sum += s.intensity;
            }
            // Together they deliver the intensity times the mean of 1 / l^2.
            const double mean = sum_inverse_square / n;
            CHECK_NEAR(sum, Spectrum(3 * mean, 6 * mean, 9 * mean), 1e-12 * mean);
        }
    }
}

TEST(sphere_light_seen_from_its_centre) {
    // Every sample is exactly one radius away, whatever the rotation: the sum is I / r^2.
    const Light light = read_light("110  37  1 2 3  2  8 4 2");
    Spectrum sum(0.0);
    for (int i = 0; i < 37; ++i) {
        const LightSample s = light.sample({1, 2, 3}, i);
        CHECK_NEAR(s.distance, 2, 1e-15);
        sum += s.intensity;
    }
    CHECK_NEAR(sum, Spectrum(2, 1, 0.5), 1e-14);
}

TEST(sphere_light_with_one_sample_is_a_point_on_its_sphere) {
    const Light light = read_light("110  1  0 0 0  0.5  1 1 1");
    CHECK_EQ(light.sample_count(), 1);
    const Vec3 x{3, 0, 0};
    const LightSample s = light.sample(x, 0);
    CHECK_NEAR(length(x + s.direction * s.distance), 0.5, 1e-14);
    CHECK_NEAR(s.intensity, Spectrum(1 / (s.distance * s.distance)), 1e-15);
}

TEST(sphere_light_samples_are_spread_evenly) {
    // An even spread over the sphere: the offsets from the centre average to nothing, their
    // squared heights to 1/3 as over the whole sphere, and no two samples crowd together
    // (each stands for an area 4 pi / n, so neighbours are about sqrt(4 pi / n) apart).
    for (const int n : {50, 400, 3000}) {
        const Light light =
            read_light(object_text(110, {static_cast<double>(n), 0, 0, 0, 1, 1, 1, 1}));
        const Vec3 x{0.3, -7, 2};
        std::vector<Vec3> offsets;
        Vec3 mean;
        double mean_y2 = 0;
        for (int i = 0; i < n; ++i) {
            const LightSample s = light.sample(x, i);
            offsets.push_back(x + s.direction * s.distance);
            mean += offsets.back() / n;
            mean_y2 += offsets.back().y * offsets.back().y / n;
        }
        CHECK(length(mean) < 2.0 / n);
        CHECK_NEAR(mean_y2, 1.0 / 3, 2.0 / n);
        const double spacing = std::sqrt(4 * std::numbers::pi / n);
        double closest = kInfinity;
        for (std::size_t i = 0; i < offsets.size(); ++i)
            for (std::size_t j = i + 1; j < offsets.size(); ++j)
                closest = std::min(closest, length(offsets[i] - offsets[j]));
        CHECK(closest > 0.5 * spacing);
    }
}

TEST(sphere_light_converges_to_the_mean_inverse_square) {
    // The sum of the samples' intensities is I times the lattice's estimate of the mean of
    // 1 / l^2 over the sphere; its error against the closed form shrinks quickly with n. The
    // tolerances (relative, for every one of 30 points at distances 1.5r to 3r) are about
    // three times the worst error seen.
    const int counts[] = {16, 64, 256, 1024, 4096};
    const double tolerance[] = {0.3, 0.05, 3e-3, 3e-4, 6e-5};
    double previous_mean_error = kInfinity;
    for (int k = 0; k < 5; ++k) {
        const int n = counts[k];
        const Light light =
            read_light(object_text(110, {static_cast<double>(n), 1, -2, 0.5, 0.7, 2, 2, 2}));
        Random random(7);  // the same points for every n
        double mean_error = 0;
        for (int p = 0; p < 30; ++p) {
            const double d = 0.7 * random.uniform(1.5, 3);
            const Vec3 x = Vec3(1, -2, 0.5) + random.unit_vector() * d;
            Spectrum sum(0.0);
            for (int i = 0; i < n; ++i) sum += light.sample(x, i).intensity;
            const double expected = 2 * mean_inverse_square(d, 0.7);
            const double error = std::fabs(sum[0] - expected) / expected;
            CHECK(error < tolerance[k]);
            mean_error += error / 30;
        }
        // Four times the samples at least halve the error.
        CHECK(mean_error < 0.5 * previous_mean_error);
        previous_mean_error = mean_error;
    }
}

TEST(sphere_light_lit_from_inside) {
    // The closed form holds inside the sphere too; 4096 samples get within 1e-3 of it.
    const Light light = read_light("110  4096  0 0 0  2  1 1 1");
    for (const double d : {0.3, 1.0, 1.5}) {
        const Vec3 x = normalized(Vec3(1, 2, -2)) * d;
        double sum = 0;
        for (int i = 0; i < 4096; ++i) sum += light.sample(x, i).intensity[0];
        CHECK_NEAR(sum / mean_inverse_square(d, 2), 1, 1e-3);
    }
}

TEST(sphere_light_is_reproducible) {
    const std::string text = "110  200  0.5 1 -2  0.8  3 2 1";
    const Light first = read_light(text);
    const Light second = read_light(text);
    std::vector<Vec3> points;
    Random random(1101);
    for (int p = 0; p < 50; ++p) points.push_back(random.in_box(6));
    // All samples at all points, as one thread computes them.
    auto all_samples = [&](const Light& light) {
        std::vector<LightSample> samples;
        for (const Vec3& x : points)
            for (int i = 0; i < light.sample_count(); ++i) samples.push_back(light.sample(x, i));
        return samples;
    };
    const std::vector<LightSample> reference = all_samples(first);
    // Two reads of the same scene give bit-identical samples.
    const std::vector<LightSample> again = all_samples(second);
    bool identical = reference.size() == again.size();
    for (std::size_t i = 0; identical && i < reference.size(); ++i)
        identical = same_bits(reference[i], again[i]);
    CHECK(identical);
    // So do threads sampling the same light at once, in the opposite order.
    std::vector<std::vector<LightSample>> results(4);
    {
        std::vector<std::jthread> threads;
        for (auto& result : results)
            threads.emplace_back([&] {
                for (std::size_t p = points.size(); p-- > 0;)
                    for (int i = first.sample_count(); i-- > 0;)
                        result.push_back(first.sample(points[p], i));
            });
    }
    for (const auto& result : results) {
        bool same = result.size() == reference.size();
        for (std::size_t k = 0; same && k < result.size(); ++k)
            same = same_bits(result[result.size() - 1 - k], reference[k]);
        CHECK(same);
    }
}

TEST(sphere_light_turns_its_lattice_from_point_to_point) {
    // Neighbouring lit points see the samples at different places (noise rather than bands).
    const Light light = read_light("110  64  0 0 0  1  1 1 1");
    const Vec3 a{3, 0.25, 1}, b{3, 0.25 + 1e-9, 1};
    int moved = 0;
    for (int i = 0; i < 64; ++i) {
        const LightSample sa = light.sample(a, i), sb = light.sample(b, i);
        const Vec3 pa = a + sa.direction * sa.distance, pb = b + sb.direction * sb.distance;
        if (length(pa - pb) > 1e-3) ++moved;
    }
    CHECK(moved > 60);
}

TEST(sphere_light_soft_shadow_through_the_tracer) {
    // A point, a blocker sphere and the sphere light on one line, in random orientations:
    // the fraction of samples whose shadow ray the tracer finds clear matches the fraction of
    // the light's sphere seen past the blocker.
    Random random(1102);
    const RenderOptions options;
    struct Setup {
        double d, r, D, b;
    };
    for (const Setup& setup : {Setup{10, 1, 5, 0.4}, Setup{8, 1.5, 3, 0.3}, Setup{6, 0.5, 2, 0.1},
                               Setup{12, 2, 4, 0.5}}) {
        // The blocker must lie wholly between the point and the nearest point of the light.
        CHECK(setup.D + setup.b < setup.d - setup.r);
        const double expected = unblocked_fraction(setup.d, setup.r, setup.D, setup.b);
        CHECK(expected > 0.3 && expected < 0.95);  // a real penumbra, neither empty nor full
        // The tolerance is about 2.5 times the largest error seen with 1024 samples.
        for (int trial = 0; trial < 5; ++trial) {
            const Vec3 x = random.in_box(3);
            const Vec3 axis = random.unit_vector();
            const Vec3 light_centre = x + axis * setup.d;
            const Vec3 blocker = x + axis * setup.D;
            const int n = 1024;
            const Scene scene = parse_scene(
                join(kTestViewer,
                     object_text(110, {static_cast<double>(n), light_centre.x, light_centre.y,
                                       light_centre.z, setup.r, 1, 1, 1}),
                     "\n", object_text(1, {setup.b, blocker.x, blocker.y, blocker.z}),
                     " 100  1 1 1  0 1 1 0 1\n"));
            Tracer tracer(scene, options);
            const Light& light = scene.lights.at(0);
            int clear = 0;
            for (int i = 0; i < n; ++i) {
                const LightSample s = light.sample(x, i);
                if (!tracer.blocked({x, s.direction}, s.distance)) ++clear;
            }
            CHECK_NEAR(static_cast<double>(clear) / n, expected, 0.01);
        }
    }
}

TEST(sphere_light_renders_alike_on_any_number_of_threads) {
    const Scene scene = parse_scene(
        "102  0 2 6  0 0 0  0.6 0 0  0 0.6 0  24 24\n"
        "110  16  1 4 1  0.7  20 20 20\n"
        "2  0  0 1 0  100  1 1 1  0 1 1 0 1\n"
        "1  0.8  0 0.8 0  100  1 0.5 0.5  0.3 20 0.7 0 1\n");
    RenderOptions one, three;
    one.threads = 1;
    three.threads = 3;
    const Raster a = render(scene, one), b = render(scene, three);
    bool identical = true;
    int penumbra = 0;  // pixels lit by some but not all samples: the test covers soft shadows
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 24; ++x) {
            identical = identical && a.at(x, y) == b.at(x, y);
            if (a.at(x, y)[0] > 0.1 && a.at(x, y)[0] < 0.5) ++penumbra;
        }
    CHECK(identical);
    CHECK(penumbra > 0);
}

TEST(sphere_light_read_errors) {
    // Columns:     1   5 7 9 11  14   19
    CHECK_CONTAINS(light_error("110 0 0 0 0  1  1 1 1"),
                   "test.in:2:5: sphere light samples must be between 1 and 4096, got 0");
    CHECK_CONTAINS(light_error("110 4097 0 0 0  1  1 1 1"),
                   "test.in:2:5: sphere light samples must be between 1 and 4096, got 4097");
    CHECK_CONTAINS(light_error("110 -3 0 0 0  1  1 1 1"),
                   "test.in:2:5: sphere light samples must be between 1 and 4096, got -3");
    CHECK_CONTAINS(light_error("110 2.5 0 0 0  1  1 1 1"),
                   "test.in:2:5: sphere light samples must be a whole number, got 2.5");
    CHECK_CONTAINS(light_error("110 8 0 0 0  0  1 1 1"),
                   "test.in:2:14: sphere light radius must be > 0, got 0");
    CHECK_CONTAINS(light_error("110 8 0 0 0  -2  1 1 1"),
                   "test.in:2:14: sphere light radius must be > 0, got -2");
    CHECK_CONTAINS(light_error("110 8 0 y 0  1  1 1 1"),
                   "test.in:2:9: expected sphere light centre (a number), got 'y'");
    CHECK_CONTAINS(light_error("110 8 0 0 0  1  1 1"),
                   "test.in:2:20: unexpected end of file: expected sphere light intensity");
    // The cap itself is allowed.
    CHECK_EQ(light_error("110 4096 0 0 0  1  1 1 1"), std::string());
}

// ---------------------------------------------------------------- directional light (113)

TEST(directional_light_is_the_same_everywhere) {
    // Travelling along (1, -2, 2), of length 3: every point sees it along (-1, 2, -2) / 3, at
    // infinite distance, with its full intensity however far away the point is.
    const Light light = read_light("113  1 -2 2  0.5 1 2");
    CHECK_EQ(light.sample_count(), 1);
    Random random(113);
    for (int i = 0; i < 1000; ++i) {
        const Vec3 x = random.in_box(i < 500 ? 10 : 1e6);
        const LightSample s = light.sample(x, 0);
        CHECK_NEAR(s.direction, Vec3(-1.0 / 3, 2.0 / 3, -2.0 / 3), 1e-15);
        CHECK(std::isinf(s.distance) && s.distance > 0);
        CHECK_NEAR(s.intensity, Spectrum(0.5, 1.0, 2.0), 0);
    }
}

TEST(directional_light_on_a_plane_by_hand) {
    // The floor y = 0 (colour (1, 0.5, 0.25), kd 0.8, ks 0.3, ke 4) lit by a light travelling
    // along (0, -1, -1) / sqrt(2): cos(theta) = 1/sqrt(2) everywhere. Rays straight down see
    // kd colour cos(theta) I; the mirror direction is (0, 1, 0), and r.s = 1/sqrt(2) too, so
    // the highlight adds ks (1/sqrt(2))^4 I = ks I / 4. Near or far, the value is the same.
    const Scene scene = parse_scene(join(kTestViewer,
                                         "2 0  0 1 0  100 1 0.5 0.25 0.3 4 0.8 0 1\n"
                                         "113  0 -1 -1  2 2 2\n"));
    RenderOptions options;
    options.reflection = false;  // the mirror ray would bring back the (black) sky anyway
    Tracer tracer(scene, options);
    const double c = 1 / std::sqrt(2.0);
    const Spectrum expected = Spectrum(2 * (0.8 * 1 * c + 0.3 / 4), 2 * (0.8 * 0.5 * c + 0.3 / 4),
                                       2 * (0.8 * 0.25 * c + 0.3 / 4));
    for (const double x : {0.0, 3.0, -250.0, 1e5})
        for (const double height : {0.5, 10.0, 1000.0})
            CHECK_NEAR(tracer.trace({{x, height, -x}, {0, -1, 0}}), expected, 1e-12);
}

TEST(directional_light_shadows_from_far_objects) {
    // A ray straight down hits the floor at (0, 0, 0); the light travels along (0, -1, 0).
    // A small sphere far up the line to the light shadows it however far it is; a sphere
    // beside that line, or below the floor, does not.
    const std::string base =
        join(kTestViewer, "2 0  0 1 0  100 1 1 1 0 1 1 0 1\n", "113  0 -1 0  1 1 1\n");
    const auto floor_value = [&](const std::string& extra) {
        const Scene scene = parse_scene(base + extra);
        return Tracer(scene, {}).trace({{0.3, 0.5, 0}, {0, -1, 0}})[0];
    };
    CHECK_NEAR(floor_value(""), 1.0, 1e-12);
    for (const double height : {2.0, 1e3, 1e6})
        CHECK_NEAR(floor_value(object_text(1, {0.5, 0.3, height, 0}) + " 100 1 1 1 0 1 1 0 1\n"),
                   0.0, 0);
    CHECK_NEAR(floor_value("1 0.5  5 1e3 0  100 1 1 1 0 1 1 0 1\n"), 1.0, 1e-12);
    CHECK_NEAR(floor_value("1 0.5  0.3 -3 0  100 1 1 1 0 1 1 0 1\n"), 1.0, 1e-12);
}

TEST(directional_light_inside_an_affine_light) {
    // The frame carries the direction the light travels: a local direction d travels along
    // F d in the world, so the sample points along -F d / |F d|, still at infinite distance
    // and with the inner light's intensity. Checked on random frames, including stretches.
    Random random(1130);
    int checked = 0;
    for (int i = 0; i < 1000; ++i) {
        Vec3 axes[3];
        for (Vec3& a : axes) a = random.in_box(2);
        if (std::fabs(dot(axes[0], cross(axes[1], axes[2]))) < 0.3) continue;
        const Vec3 o = random.in_box(3), d = random.in_box(1), x = random.in_box(5);
        if (length(d) < 0.1) continue;
        const std::string text =
            object_text(112, {o.x, o.y, o.z, axes[0].x, axes[0].y, axes[0].z, axes[1].x, axes[1].y,
                              axes[1].z, axes[2].x, axes[2].y, axes[2].z}) +
            " " + object_text(113, {d.x, d.y, d.z, 1, 2, 3});
        const Vec3 world = d.x * axes[0] + d.y * axes[1] + d.z * axes[2];
        const LightSample s = read_light(text).sample(x, 0);
        CHECK_NEAR(s.direction, -world / length(world), 1e-12);
        CHECK(std::isinf(s.distance));
        CHECK_NEAR(s.intensity, Spectrum(1.0, 2.0, 3.0), 0);
        ++checked;
    }
    CHECK(checked > 300);
    // By hand: a quarter turn about z takes local x to world y, so a light travelling along
    // local -x travels along world -y: straight down.
    const LightSample down =
        read_light("112 5 5 5  0 1 0  -1 0 0  0 0 1  113 -1 0 0  1 1 1").sample({1, 2, 3}, 0);
    CHECK_NEAR(down.direction, Vec3(0, 1, 0), 1e-15);
}

TEST(directional_light_read_errors) {
    // In "113 0 0 0  1 1 1" the direction starts at column 5, the intensity at 12.
    CHECK_CONTAINS(light_error("113 0 0 0  1 1 1"),
                   "test.in:2:5: directional light direction must have a non-zero length");
    // However long or short, a non-zero vector is a direction.
    CHECK_EQ(light_error("113 1e200 1e200 0  1 1 1"), std::string());
    CHECK_EQ(light_error("113 1e-200 1e-200 0  1 1 1"), std::string());
    CHECK_CONTAINS(light_error("113 0 -1 0  1 z 1"),
                   "test.in:2:15: expected directional light intensity (a number), got 'z'");
    CHECK_CONTAINS(light_error("113 0 -1 0  1 1"),
                   "test.in:2:16: unexpected end of file: expected directional light intensity");
    CHECK_CONTAINS(light_error("112 0 0 0  1 0 0  0 1 0  0 0 1  113 0 0 0  1 1 1"),
                   "test.in:2:37: directional light direction must have a non-zero length");
    // A tiny direction is still a direction.
    CHECK_NEAR(read_light("113 0 -1e-100 0  1 1 1").sample({0, 0, 0}, 0).direction, Vec3(0, 1, 0),
               0);
}
