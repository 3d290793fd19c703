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

// A point light's parameters (101 with falloff, 104 without). The tracer samples such a
// light inline (Light::point): most scenes' lights are points, and through the table each
// was two calls and a sample returned through memory for every light at every hit.
struct PointLight {
    Vec3 position;
    Spectrum intensity;
    bool falloff;
};

// The point light's one sample at `point`.
inline LightSample sample_point_light(const PointLight& light, const Vec3& point) {
    const Vec3 to_light = light.position - point;
    const double distance = length(to_light);
    // A point sitting exactly on the light receives nothing rather than a division by zero.
    if (!(distance > 0)) return {{0, 0, 1}, 0, Spectrum(0.0)};
    const double falloff = light.falloff ? 1 / (distance * distance) : 1;
    return {to_light / distance, distance, light.intensity * falloff};
}

using LightData = std::shared_ptr<const void>;
using ReadLightFn = LightData(SceneReader& reader);
// How many samples the light takes (fixed for each light, so renders are reproducible).
using SampleCountFn = int(const void* light);
using SampleLightFn = LightSample(const void* light, const Vec3& point, int index);
// The light's parameters where it is a point light (its samples are sample_point_light's).
using PointOfFn = const PointLight*(const void* light);

struct LightType {
    int id;
    const char* name;
    ReadLightFn* read;
    SampleCountFn* sample_count;
    SampleLightFn* sample;
    // Point lights only; nullptr for the rest.
    PointOfFn* point = nullptr;
};

struct Light {
    const LightType* type = nullptr;
    LightData data;

    int sample_count() const { return type->sample_count(data.get()); }
    LightSample sample(const Vec3& point, int index) const {
        return type->sample(data.get(), point, index);
    }
    // The parameters of a point light; nullptr for any other light.
    const PointLight* point() const {
        return type->point != nullptr ? type->point(data.get()) : nullptr;
    }
};

std::span<const LightType> light_types();
const LightType* find_light_type(int id);

}  // namespace rt
