// The optics a surface applies to a ray: mirror reflection, refraction by Snell's law and the
// Fresnel reflectance of a dielectric.
#pragma once

#include <optional>

#include "rt/vec.h"

namespace rt {

// The mirror direction of `incoming` about a unit normal. Inline: every hit the tracer shades
// asks for it.
inline Vec3 reflect(const Vec3& incoming, const Vec3& normal) {
    return incoming - 2 * dot(incoming, normal) * normal;
}
// The direction refracted by Snell's law for a unit incoming direction and a unit normal that
// faces it (dot(incoming, normal) <= 0), where eta = n1 / n2. Nothing on total internal
// reflection.
std::optional<Vec3> refract(const Vec3& incoming, const Vec3& normal, double eta);
// The Fresnel reflectance F = (R_s + R_p) / 2 of unpolarised light meeting, at an angle whose
// cosine is cos_i, the boundary from a medium of index n1 into one of index n2: the fraction
// reflected (1 - F passes through). 1 on total internal reflection.
double fresnel_reflectance(double cos_i, double n1, double n2);

}  // namespace rt
