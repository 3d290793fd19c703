// The optics a surface applies to a ray: mirror reflection, refraction by Snell's law and the
// Fresnel reflectance of a dielectric.
#pragma once

#include <bit>
#include <cstdint>
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

// False only where a highlight ks * pow(cos_angle, ke) is surely too small to change a sum
// whose smallest term is `smallest` (all terms positive): below half the last place of each,
// which round to nearest leaves as it is, bit for bit. There the highlight need not be
// computed: pow is a few per cent of a render with sharp highlights. Anything it cannot judge
// (a zero, tiny or infinite smallest term, NaN, cos_angle of 1 or more, ke <= 0) may change
// the sum.
inline bool highlight_may_count(double smallest, double ks, double cos_angle, double ke) {
    constexpr double kLog2E = 1.4426950408889634;
    // The exponent of a positive finite double (-1023 for a subnormal, which is then below
    // 2^(exponent + 1), as every other is).
    const auto exponent = [](double v) {
        return static_cast<int>(std::bit_cast<std::uint64_t>(v) >> 52) - 1023;
    };
    // Above 2^-960 the bound below stays far above where pow's result would be subnormal.
    if (!(smallest >= 0x1p-960) || !(smallest < 0x1p1023) || !(ks > 0) || !(ks < 0x1p1023))
        return true;
    // For c in (0, 1), ln c <= c - 1, so c^ke <= 2^-fall with fall = ke (1 - c) log2 e, and
    // the computed highlight is below 2 ks c^ke < 2^(exponent(ks) + 2 - fall) (pow's and the
    // product's roundings are far below the factor 2). Half the last place of any term is at
    // least 2^(exponent(smallest) - 53), so fall at least exponent(ks) - exponent(smallest) +
    // 55 suffices; one more covers the rounding of fall itself.
    const double fall = ke * (1 - cos_angle) * kLog2E;
    return !(fall > exponent(ks) - exponent(smallest) + 56);
}

}  // namespace rt
