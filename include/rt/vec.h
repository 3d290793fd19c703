// Three-component vectors of doubles: points, directions and normals.
#pragma once

#include <cmath>

namespace rt {

struct Vec3 {
    double x = 0, y = 0, z = 0;

    constexpr Vec3() = default;
    constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}

    constexpr double operator[](int axis) const { return axis == 0 ? x : axis == 1 ? y : z; }

    constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    constexpr Vec3& operator+=(const Vec3& v) {
        x += v.x;
        y += v.y;
        z += v.z;
        return *this;
    }
    constexpr Vec3& operator-=(const Vec3& v) { return *this += -v; }
    constexpr Vec3& operator*=(double s) {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
    constexpr bool operator==(const Vec3&) const = default;
};

constexpr Vec3 operator+(Vec3 a, const Vec3& b) { return a += b; }
constexpr Vec3 operator-(Vec3 a, const Vec3& b) { return a -= b; }
constexpr Vec3 operator*(Vec3 v, double s) { return v *= s; }
constexpr Vec3 operator*(double s, Vec3 v) { return v *= s; }
constexpr Vec3 operator/(Vec3 v, double s) { return v *= 1.0 / s; }

constexpr double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
constexpr double length_squared(const Vec3& v) { return dot(v, v); }
inline double length(const Vec3& v) { return std::sqrt(dot(v, v)); }
inline Vec3 normalized(const Vec3& v) { return v / length(v); }
constexpr Vec3 component_min(const Vec3& a, const Vec3& b) {
    return {a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y, a.z < b.z ? a.z : b.z};
}
constexpr Vec3 component_max(const Vec3& a, const Vec3& b) {
    return {a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y, a.z > b.z ? a.z : b.z};
}
// std::fmax(a, b) for a and b that are not negative (absolute values), NaN rule included (a
// NaN gives way to the other), without the call to the library that std::fmax compiles to
// on x86-64: the tracer asks this twice for every ray query.
constexpr double max_of_magnitudes(double a, double b) {
    if (a != a) return b;
    if (b != b) return a;
    return a < b ? b : a;
}
// The largest absolute component: a cheap measure of how far a point is from the origin.
inline double max_abs_component(const Vec3& v) {
    return max_of_magnitudes(std::fabs(v.x), max_of_magnitudes(std::fabs(v.y), std::fabs(v.z)));
}

}  // namespace rt
