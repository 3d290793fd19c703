// Point lights: with inverse-square falloff (ID 101) and without (ID 104). Both read a
// position and an intensity.
#include "lights/lights.h"
#include "rt/ray.h"
#include "rt/reader.h"

namespace rt::point_light {

namespace {
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
    return sample_point_light(*static_cast<const PointLight*>(light), point);
}

const PointLight* point_of(const void* light) { return static_cast<const PointLight*>(light); }

}  // namespace rt::point_light
