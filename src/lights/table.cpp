// The table of light types that have a position. The ambient light (103) is not sampled; the
// reader adds it to the scene's ambient intensity.
#include "lights/lights.h"
#include "scene/id_table.h"

namespace rt {

namespace {

constexpr std::array kLightTypes{
    LightType{101, "point light", point_light::read_with_falloff, point_light::sample_count,
              point_light::sample, point_light::point_of},
    LightType{104, "point light without falloff", point_light::read_without_falloff,
              point_light::sample_count, point_light::sample, point_light::point_of},
    LightType{109, "spot light", spot_light::read, spot_light::sample_count, spot_light::sample},
    LightType{110, "sphere light", sphere_light::read, sphere_light::sample_count,
              sphere_light::sample},
    LightType{112, "affine light", affine_light::read, affine_light::sample_count,
              affine_light::sample},
    LightType{113, "directional light", directional_light::read, directional_light::sample_count,
              directional_light::sample},
};

static_assert(strictly_sorted_by_id(kLightTypes), "rows sorted by ID, each ID once");

}  // namespace

std::span<const LightType> light_types() { return kLightTypes; }

const LightType* find_light_type(int id) { return find_by_id(kLightTypes, id); }

}  // namespace rt
