// Surfaces: given a point, they return the parameters of the Phong model there.
#pragma once

#include <memory>
#include <span>

#include "rt/spectrum.h"
#include "rt/vec.h"

namespace rt {

class SceneReader;

// The shading parameters at one point. The simple surface (ID 100) sets the first six; the
// glass surface (114) sets fresnel and absorption and leaves kt unused.
struct Material {
    Spectrum colour{1.0};
    double ks = 0;   // specular highlight, and (unless fresnel) mirror reflection
    double ke = 1;   // specular exponent
    double kd = 1;   // diffuse
    double kt = 0;   // transmission (unless fresnel)
    double ior = 1;  // refractive index of the material behind the surface
    // A dielectric: mirror and transmission weights are F and 1 - F from the Fresnel
    // equations instead of ks and kt.
    bool fresnel = false;
    Spectrum absorption{0.0};  // per unit of distance travelled behind the surface
};

using SurfaceData = std::shared_ptr<const void>;
using ReadSurfaceFn = SurfaceData(SceneReader& reader);
using EvaluateSurfaceFn = Material(const void* surface, const Vec3& point);

struct SurfaceType {
    int id;
    const char* name;
    ReadSurfaceFn* read;
    EvaluateSurfaceFn* evaluate;
};

struct Surface {
    const SurfaceType* type = nullptr;
    SurfaceData data;

    Material at(const Vec3& point) const { return type->evaluate(data.get(), point); }
};

// Surfaces are shared: every primitive that says 106 shares the current default.
using SurfacePtr = std::shared_ptr<const Surface>;

std::span<const SurfaceType> surface_types();
const SurfaceType* find_surface_type(int id);

}  // namespace rt
