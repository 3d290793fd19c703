// The ray-sphere test of the sphere (1), in one place: the sphere's own intersect function
// and the hierarchy's packed leaves (accel/object_index.cpp), which test spheres inline
// without a call, both run this code, so they find the same hits to the bit. Inlined always:
// the hierarchy's walks are large functions, and GCC's limits on their growth otherwise keep
// these out of line there, a call per sphere (spheres-10k's render, +3 % instructions).
#pragma once

#include <cmath>
#include <utility>

#include "rt/primitive.h"

namespace rt {

// The quadratic t^2 + 2bt + c = 0 of a unit-direction ray and a sphere, as sphere_crossing
// computes it: b, the discriminant r^2 - |oc - b d|^2 (b^2 - c, without the cancellation of
// b^2 - c when the sphere is far away and small) and c.
struct SphereQuadratic {
    double b;
    double discriminant;
    double c;
};

// The distance of the nearer of the quadratic's roots in range (the farther where the nearer
// is out of it), or false when neither is in range: the root of larger magnitude first, then
// the other as c / q, with no cancellation.
[[gnu::always_inline]] inline bool quadratic_crossing(const SphereQuadratic& k, Interval range,
                                                      double& t) {
    const double q = -k.b - std::copysign(std::sqrt(k.discriminant), k.b);
    double near = q;
    double far = q != 0 ? k.c / q : 0;
    if (near > far) std::swap(near, far);
    t = range.contains(near) ? near : far;
    return range.contains(t);
}

// True only where quadratic_crossing would return false, decided without its square root
// and division (which are most of a crossed sphere's cost); false where that is not sure.
// Rays of a scene of overlapping spheres mostly enter boxes of spheres that lie behind them,
// or beyond the nearest hit found so far (docs/performance.md, "Spheres decided early").
// Every step is a comparison that rounding cannot turn: a product's or a difference's sign
// is trusted only with a relative margin of 2^-50, eight times a double's rounding.
[[gnu::always_inline]] inline bool quadratic_surely_out_of_range(const SphereQuadratic& k,
                                                                 Interval range) {
    if (!(range.t_min >= 0)) return false;
    // The centre behind the origin (b > 0) and the origin outside (c > 0): the computed q is
    // at most -b < 0, and c / q negative, so neither root is in a range above zero.
    if (k.b > 0 && k.c > 0) return true;
    // Both roots at or beyond t_max: the centre ahead (b < 0), the origin outside (c > 0),
    // and sqrt(discriminant) below g = -b - t_max, so that q (-b plus the root, rounded)
    // lies in [-b, -b + g]. Then q is beyond t_max, and so is c / q where c is at least
    // (-b + g) t_max.
    constexpr double kNormal = 0x1p-500;  // far from underflow: every relative bound holds
    const double g = -k.b - range.t_max;
    if (!(k.b < 0 && k.c > 0 && g > kNormal && range.t_max > kNormal &&
          k.discriminant < g * g * (1 - 0x1p-48)))
        return false;
    const double product = (-k.b + g) * range.t_max;
    return k.c - product > 0x1p-50 * (k.c + product);
}

// The distance of the nearer of the ray's crossings with the sphere in range (the farther
// where the nearer is out of it), or false when neither is in range. The ray's direction
// must be unit length.
[[gnu::always_inline]] inline bool sphere_crossing(const SphereParameters& s, const Ray& ray,
                                                   Interval range, double& t) {
    const Vec3 oc = ray.origin - s.centre;
    const double b = dot(oc, ray.direction);
    const Vec3 perpendicular = oc - b * ray.direction;
    const double discriminant = s.radius_squared - length_squared(perpendicular);
    if (discriminant < 0) return false;
    // c only here: most spheres whose boxes a ray enters it misses, and computing c for
    // them too (or through a function returning the whole quadratic) cost shells-4000 4 to
    // 8 % more instructions.
    const SphereQuadratic quadratic{b, discriminant, length_squared(oc) - s.radius_squared};
    if (quadratic_surely_out_of_range(quadratic, range)) return false;
    return quadratic_crossing(quadratic, range, t);
}

// The quadratic sphere_crossing computes, whole (for tests, which check that the two agree).
inline SphereQuadratic sphere_quadratic(const SphereParameters& s, const Ray& ray) {
    const Vec3 oc = ray.origin - s.centre;
    const double b = dot(oc, ray.direction);
    const Vec3 perpendicular = oc - b * ray.direction;
    return {b, s.radius_squared - length_squared(perpendicular),
            length_squared(oc) - s.radius_squared};
}

// The sphere's intersect (PrimitiveFunctions::intersect), for the table and the leaves alike.
[[gnu::always_inline]] inline bool sphere_hit(const SphereParameters& s, const Ray& ray,
                                              Interval range, Hit& hit) {
    double t = 0;
    if (!sphere_crossing(s, ray, range, t)) return false;
    hit.t = t;
    hit.part = 0;
    return true;
}

}  // namespace rt
