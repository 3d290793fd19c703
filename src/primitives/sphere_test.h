// The ray-sphere test of the sphere (1), in one place: the sphere's own intersect function
// and the hierarchy's packed leaves (accel/object_index.cpp), which test spheres inline
// without a call, both run this code, so they find the same hits to the bit.
#pragma once

#include <cmath>
#include <utility>

#include "rt/primitive.h"

namespace rt {

// The distance of the nearer of the ray's crossings with the sphere in range (the farther
// where the nearer is out of it), or false when neither is in range.
inline bool sphere_crossing(const SphereParameters& s, const Ray& ray, Interval range, double& t) {
    // With a unit direction the quadratic is t^2 + 2bt + c = 0.
    const Vec3 oc = ray.origin - s.centre;
    const double b = dot(oc, ray.direction);
    // r^2 - |oc - b d|^2 is the discriminant without the cancellation of b^2 - c when the
    // sphere is far away and small.
    const Vec3 perpendicular = oc - b * ray.direction;
    const double discriminant = s.radius_squared - length_squared(perpendicular);
    if (discriminant < 0) return false;
    const double c = length_squared(oc) - s.radius_squared;
    // The root of larger magnitude first, then the other as c / q: no cancellation.
    const double q = -b - std::copysign(std::sqrt(discriminant), b);
    double near = q;
    double far = q != 0 ? c / q : 0;
    if (near > far) std::swap(near, far);
    t = range.contains(near) ? near : far;
    return range.contains(t);
}

// The sphere's intersect (PrimitiveFunctions::intersect), for the table and the leaves alike.
inline bool sphere_hit(const SphereParameters& s, const Ray& ray, Interval range, Hit& hit) {
    double t = 0;
    if (!sphere_crossing(s, ray, range, t)) return false;
    hit.t = t;
    hit.part = 0;
    return true;
}

}  // namespace rt
