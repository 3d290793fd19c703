#include "rt/optics.h"

#include <algorithm>
#include <cmath>

namespace rt {

std::optional<Vec3> refract(const Vec3& incoming, const Vec3& normal, double eta) {
    const double cos_i = -dot(incoming, normal);
    const double k = 1 - eta * eta * (1 - cos_i * cos_i);
    if (k < 0) return std::nullopt;
    return normalized(eta * incoming + (eta * cos_i - std::sqrt(k)) * normal);
}

double fresnel_reflectance(double cos_i, double n1, double n2) {
    cos_i = std::clamp(cos_i, 0.0, 1.0);
    const double eta = n1 / n2;
    const double sin2_t = eta * eta * (1 - cos_i * cos_i);  // Snell's law, squared
    if (sin2_t >= 1) return 1;                              // total internal reflection
    const double cos_t = std::sqrt(1 - sin2_t);
    const double s = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    const double p = (n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i);
    return (s * s + p * p) / 2;
}

}  // namespace rt
