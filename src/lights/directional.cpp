// Directional light (ID 113): direction the light travels; intensity. A light at infinity:
// every point sees it along the opposite of its direction with the same intensity (no
// falloff), and any object on that whole half-line shadows it.
#include "lights/lights.h"
#include "rt/ray.h"
#include "rt/reader.h"

namespace rt::directional_light {

namespace {
struct DirectionalLight {
    Vec3 to_light;  // unit vector against the direction the light travels (s in the Phong model)
    Spectrum intensity;
};
}  // namespace

LightData read(SceneReader& reader) {
    const Vec3 direction = reader.direction("directional light direction");
    const Vec3 i = reader.vec3("directional light intensity");
    return std::make_shared<const DirectionalLight>(
        DirectionalLight{-direction, {i.x, i.y, i.z}});
}

int sample_count(const void*) { return 1; }

LightSample sample(const void* light, const Vec3&, int) {
    const auto& l = *static_cast<const DirectionalLight*>(light);
    return {l.to_light, kInfinity, l.intensity};
}

}  // namespace rt::directional_light
