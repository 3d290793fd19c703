// Sphere light (ID 110): samples n; centre; radius; intensity. An area light sampled at n
// points spread evenly over its sphere, each carrying intensity / n with inverse-square
// falloff, so that objects cast soft shadows.
//
// The n points are a spherical Fibonacci lattice, each computed when it is sampled: storing
// them would cost 24n bytes per light, and a small scene could then ask for gigabytes. Each
// lit point sees the lattice turned by a rotation chosen by a hash of that point's
// coordinates: neighbouring points then see different sample positions, which turns the
// bands a fixed lattice leaves in a penumbra into fine noise (and noise, unlike bands,
// averages out under supersampling). A sample depends only on the light, its index and the
// lit point, so renders are the same whatever the threads or the order of the work.
#include <bit>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "lights/lights.h"
#include "rt/ray.h"
#include "rt/reader.h"

namespace rt::sphere_light {

namespace {

struct SphereLight {
    Vec3 centre;
    double radius;
    Spectrum sample_intensity;  // intensity / n: what each sample carries before falloff
    int n;                      // the number of samples
};

// Point i of the n of a spherical Fibonacci lattice: heights evenly spaced (so each point
// stands for an equal area, by Archimedes' hat-box theorem) and longitudes stepped by the
// golden angle, which keeps neighbouring heights far apart in longitude.
Vec3 fibonacci_point(int i, int n) {
    // The golden ratio's fractional part: turning by this fraction of a full circle each step
    // is turning by the golden angle.
    const double golden_fraction = std::numbers::phi - 1;
    const double z = 1 - (2.0 * i + 1) / n;
    const double r = std::sqrt(1 - z * z);
    // Taking the fractional part first keeps the angle accurate for large i.
    const double turns = i * golden_fraction - std::floor(i * golden_fraction);
    const double longitude = 2 * std::numbers::pi * turns;
    return {r * std::cos(longitude), r * std::sin(longitude), z};
}

// The splitmix64 finaliser: a cheap bijective mix in which every input bit affects every
// output bit.
std::uint64_t mix(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

// A unit quaternion (w, v) chosen by the lit point's coordinates. It need not be uniformly
// distributed over all rotations: every rotation of the lattice is an equally good point set,
// and only the decorrelation between neighbouring points matters.
struct Rotation {
    double w = 1;
    Vec3 v;

    Vec3 apply(const Vec3& p) const {
        const Vec3 t = 2 * cross(v, p);
        return p + w * t + cross(v, t);
    }
};

Rotation rotation_for(const Vec3& point) {
    // Adding 0.0 turns -0.0 into +0.0, so that both hash alike.
    std::uint64_t h = 0;
    for (const double c : {point.x, point.y, point.z})
        h = mix(h ^ std::bit_cast<std::uint64_t>(c + 0.0)) + 0x9e3779b97f4a7c15ULL;
    double q[4];
    for (double& component : q) {
        h = mix(h + 0x9e3779b97f4a7c15ULL);
        component = static_cast<double>(h >> 11) * 0x1.0p-52 - 1;  // in [-1, 1)
    }
    const double length2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    // Nearly zero only by a vanishingly unlikely hash; the lattice is then used as it is.
    if (!(length2 > 1e-6)) return {};
    const double scale = 1 / std::sqrt(length2);
    return {q[0] * scale, {q[1] * scale, q[2] * scale, q[3] * scale}};
}

}  // namespace

LightData read(SceneReader& reader) {
    const int n = static_cast<int>(reader.whole("sphere light samples", 1, kMaxSamples));
    const Vec3 centre = reader.vec3("sphere light centre");
    const double radius = reader.positive("sphere light radius");
    const Vec3 i = reader.vec3("sphere light intensity");
    const Spectrum sample_intensity = Spectrum(i.x, i.y, i.z) * (1.0 / n);
    return std::make_shared<const SphereLight>(SphereLight{centre, radius, sample_intensity, n});
}

int sample_count(const void* light) { return static_cast<const SphereLight*>(light)->n; }

LightSample sample(const void* light, const Vec3& point, int index) {
    const auto& l = *static_cast<const SphereLight*>(light);
    assert(index >= 0 && index < sample_count(light));
    const Vec3 on_light =
        l.centre + l.radius * rotation_for(point).apply(fibonacci_point(index, l.n));
    const Vec3 to_light = on_light - point;
    const double distance = length(to_light);
    // A point sitting exactly on a sample receives nothing from it rather than a division by
    // zero.
    if (!(distance > 0)) return {{0, 0, 1}, 0, Spectrum(0.0)};
    return {to_light / distance, distance, l.sample_intensity * (1 / (distance * distance))};
}

}  // namespace rt::sphere_light
