// Light sources that illuminate from a position (the ambient light is kept apart, in the scene).
#pragma once

#include <memory>
#include <span>

#include "rt/spectrum.h"
#include "rt/vec.h"

namespace rt {

class SceneReader;

// One sample of a light as seen from the point being lit.
struct LightSample {
    Vec3 direction;      // unit vector from the point toward the light (s in the Phong model)
    double distance;     // how far a shadow ray must reach; kInfinity for a light at infinity
    Spectrum intensity;  // the intensity arriving at the point, falloff already applied
};

using LightData = std::shared_ptr<const void>;
using ReadLightFn = LightData(SceneReader& reader);
// How many samples the light takes (fixed for each light, so renders are reproducible).
using SampleCountFn = int(const void* light);
using SampleLightFn = LightSample(const void* light, const Vec3& point, int index);

struct LightType {
    int id;
    const char* name;
    ReadLightFn* read;
    SampleCountFn* sample_count;
    SampleLightFn* sample;
};

struct Light {
    const LightType* type = nullptr;
    LightData data;

    int sample_count() const { return type->sample_count(data.get()); }
    LightSample sample(const Vec3& point, int index) const {
        return type->sample(data.get(), point, index);
    }
};

std::span<const LightType> light_types();
const LightType* find_light_type(int id);

}  // namespace rt
