// The functions each light's source file provides, for the table in lights/table.cpp.
#pragma once

#include "rt/light.h"

namespace rt::point_light {
ReadLightFn read_with_falloff;
ReadLightFn read_without_falloff;
SampleCountFn sample_count;
SampleLightFn sample;
PointOfFn point_of;
}  // namespace rt::point_light

namespace rt::spot_light {
ReadLightFn read;
SampleCountFn sample_count;
SampleLightFn sample;
}  // namespace rt::spot_light

namespace rt::sphere_light {
// The most samples a sphere light may ask for, so that no input allocates without bound.
// Already 1024 samples put the fraction of the light seen past an obstacle within about 1/255
// (one 8-bit level) of its exact value.
inline constexpr long kMaxSamples = 4096;
ReadLightFn read;
SampleCountFn sample_count;
SampleLightFn sample;
}  // namespace rt::sphere_light

namespace rt::directional_light {
ReadLightFn read;
SampleCountFn sample_count;
SampleLightFn sample;
}  // namespace rt::directional_light

namespace rt::affine_light {
ReadLightFn read;
SampleCountFn sample_count;
SampleLightFn sample;
}  // namespace rt::affine_light
