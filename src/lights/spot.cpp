// Spot light (ID 109): position; direction; cos of cut-off angle; exponent; intensity. A point
// light with inverse-square falloff whose light is confined to a cone about its direction and
// fades toward the cone's edge as cos^exponent of the angle from the axis.
#include <algorithm>
#include <cmath>

#include "lights/lights.h"
#include "rt/ray.h"
#include "rt/reader.h"

namespace rt::spot_light {

namespace {
struct SpotLight {
    Vec3 position;
    Vec3 axis;  // unit direction the light shines along
    double cos_cutoff;
    double exponent;
    Spectrum intensity;
};
}  // namespace

LightData read(SceneReader& reader) {
    const Vec3 position = reader.vec3("spot light position");
    const Vec3 axis = reader.direction("spot light direction");
    const Location cutoff_at = reader.next_location();
    const double cos_cutoff = reader.number("spot light cos of cut-off angle");
    if (!(cos_cutoff >= -1 && cos_cutoff <= 1))
        reader.fail(cutoff_at, "spot light cos of cut-off angle must be between -1 and 1, got " +
                                   format_number(cos_cutoff));
    const double exponent = reader.non_negative("spot light exponent");
    const Vec3 i = reader.vec3("spot light intensity");
    return std::make_shared<const SpotLight>(
        SpotLight{position, axis, cos_cutoff, exponent, {i.x, i.y, i.z}});
}

int sample_count(const void*) { return 1; }

LightSample sample(const void* light, const Vec3& point, int) {
    const auto& l = *static_cast<const SpotLight*>(light);
    const Vec3 to_light = l.position - point;
    const double distance = length(to_light);
    // A point sitting exactly on the light receives nothing rather than a division by zero.
    if (!(distance > 0)) return {{0, 0, 1}, 0, Spectrum(0.0)};
    const Vec3 direction = to_light / distance;
    // The cosine of the angle between the light's axis and the way the light travels to the
    // point; a point at exactly the cut-off angle is lit.
    const double cos_angle = -dot(direction, l.axis);
    if (cos_angle < l.cos_cutoff) return {direction, distance, Spectrum(0.0)};
    // A cut-off wider than 90 degrees lets light reach points behind the spot, where the
    // cosine is negative: they take cos = 0, so that no power of it turns negative or NaN
    // (with exponent 0 they are lit fully, as 0^0 = 1).
    const double spread = std::pow(std::max(cos_angle, 0.0), l.exponent);
    return {direction, distance, l.intensity * (spread / (distance * distance))};
}

}  // namespace rt::spot_light
