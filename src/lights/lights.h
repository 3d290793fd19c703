// The functions each light's source file provides, for the table in lights/table.cpp.
#pragma once

#include "rt/light.h"

namespace rt::point_light {
ReadLightFn read_with_falloff;
ReadLightFn read_without_falloff;
SampleCountFn sample_count;
SampleLightFn sample;
}  // namespace rt::point_light

namespace rt::affine_light {
ReadLightFn read;
SampleCountFn sample_count;
SampleLightFn sample;
}  // namespace rt::affine_light
