// Affine light (ID 112): O; X; Y; Z; then a light (ID and numbers) placed in that frame.
// The lit point is taken into the local frame and the inner light sampled there; the sample's
// position is carried back to the world, where the direction and distance are measured again.
// The intensity is the inner light's, falloff included, measured in local units: as the
// original warns, a 1/r^2 light only behaves under frames that scale all distances alike.
#include <cmath>

#include "scene/affine_frame.h"
#include "lights/lights.h"
#include "rt/ray.h"
#include "rt/reader.h"

namespace rt::affine_light {

namespace {
struct AffineLight {
    AffineFrame frame;
    Light inner;
};
}  // namespace

LightData read(SceneReader& reader) {
    const AffineFrame frame = read_affine_frame(reader, "affine light");
    Light inner = reader.light("affine inner light");
    return std::make_shared<const AffineLight>(AffineLight{frame, std::move(inner)});
}

int sample_count(const void* light) {
    return static_cast<const AffineLight*>(light)->inner.sample_count();
}

LightSample sample(const void* light, const Vec3& point, int index) {
    const auto& a = *static_cast<const AffineLight*>(light);
    const LightSample local = a.inner.sample(a.frame.to_local_point(point), index);
    if (std::isinf(local.distance))
        return {normalized(a.frame.to_world_direction(local.direction)), kInfinity,
                local.intensity};
    // The world position of the sample is O + F(local point + direction * distance); its
    // offset from the lit point is F(direction * distance), computed directly so the round
    // trip through the local frame adds no error.
    const Vec3 to_light = a.frame.to_world_direction(local.direction * local.distance);
    const double distance = length(to_light);
    // A point sitting on the light receives nothing, as with the point lights.
    if (!(distance > 0)) return {{0, 0, 1}, 0, Spectrum(0.0)};
    return {to_light / distance, distance, local.intensity};
}

}  // namespace rt::affine_light
