#include "rtpp/transform.h"

#include <cmath>
#include <numbers>

namespace rtpp {

Frame compose(const Frame& outer, const Frame& inner) {
    return {outer.point(inner.origin), outer.direction(inner.x), outer.direction(inner.y),
            outer.direction(inner.z)};
}

Frame translation(const Vec3& offset) {
    Frame f;
    f.origin = offset;
    return f;
}

Frame scaling(const Vec3& factors) {
    Frame f;
    f.x = {factors.x, 0, 0};
    f.y = {0, factors.y, 0};
    f.z = {0, 0, factors.z};
    return f;
}

namespace {
// The angle reduced to [0, 360), and whether it is a whole number of degrees.
double reduce(double degrees) {
    double r = std::fmod(degrees, 360.0);
    if (r < 0) r += 360.0;
    return r;
}
}  // namespace

double sin_degrees(double degrees) {
    const double r = reduce(degrees);
    if (r == 0 || r == 180) return 0;
    if (r == 90) return 1;
    if (r == 270) return -1;
    if (r == 30 || r == 150) return 0.5;
    if (r == 210 || r == 330) return -0.5;
    return std::sin(degrees * std::numbers::pi / 180);
}

double cos_degrees(double degrees) {
    const double r = reduce(degrees);
    if (r == 90 || r == 270) return 0;
    if (r == 0) return 1;
    if (r == 180) return -1;
    if (r == 60 || r == 300) return 0.5;
    if (r == 120 || r == 240) return -0.5;
    return std::cos(degrees * std::numbers::pi / 180);
}

double tan_degrees(double degrees) {
    const double r = std::fmod(reduce(degrees), 180.0);
    if (r == 45) return 1;
    if (r == 135) return -1;
    return sin_degrees(degrees) / cos_degrees(degrees);
}

Vec3 unit(const Vec3& v) {
    const double length = std::sqrt(rt::dot(v, v));
    return {v.x / length, v.y / length, v.z / length};
}

Frame rotation(double degrees, const Vec3& axis) {
    // Rodrigues: R = c I + s [k]x + (1 - c) k k^T, written out by columns (the images of the
    // x, y and z axes).
    const Vec3 k = unit(axis);
    const double c = cos_degrees(degrees);
    const double s = sin_degrees(degrees);
    const double t = 1 - c;
    Frame f;
    f.x = {c + t * k.x * k.x, t * k.x * k.y + s * k.z, t * k.x * k.z - s * k.y};
    f.y = {t * k.x * k.y - s * k.z, c + t * k.y * k.y, t * k.y * k.z + s * k.x};
    f.z = {t * k.x * k.z + s * k.y, t * k.y * k.z - s * k.x, c + t * k.z * k.z};
    return f;
}

}  // namespace rtpp
