// Point lights: with inverse-square falloff (ID 101) and without (ID 104). Both read a
// position and an intensity.
#include "lights/lights.h"
#include "rt/ray.h"
#include "rt/reader.h"

namespace rt::point_light {

namespace {
struct PointLight {
    Vec3 position;
    Spectrum intensity;
    bool falloff;
};

LightData read(SceneReader& reader, bool falloff) {
    const Vec3 position = reader.vec3("point light position");
    const Vec3 i = reader.vec3("point light intensity");
    return std::make_shared<const PointLight>(PointLight{position, {i.x, i.y, i.z}, falloff});
}
}  // namespace

LightData read_with_falloff(SceneReader& reader) { return read(reader, true); }
LightData read_without_falloff(SceneReader& reader) { return read(reader, false); }

int sample_count(const void*) { return 1; }

LightSample sample(const void* light, const Vec3& point, int) {
    const auto& l = *static_cast<const PointLight*>(light);
    const Vec3 to_light = l.position - point;
    const double distance = length(to_light);
    // A point sitting exactly on the light receives nothing rather than a division by zero.
    if (!(distance > 0)) return {{0, 0, 1}, 0, Spectrum(0.0)};
    const double falloff = l.falloff ? 1 / (distance * distance) : 1;
    return {to_light / distance, distance, l.intensity * falloff};
}

}  // namespace rt::point_light
