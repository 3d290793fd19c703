// Rays and the bounds that primitives report.
#pragma once

#include <limits>

#include "rt/vec.h"

namespace rt {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A ray o + t d. The creator normalises d, so t is a distance in the ray's frame.
struct Ray {
    Vec3 origin;
    Vec3 direction;

    constexpr Vec3 at(double t) const { return origin + direction * t; }
};

// Hits are accepted only for t_min < t < t_max. t_max is the best hit found so far, so an
// intersect routine can give up as soon as it knows it cannot beat it.
struct Interval {
    double t_min = 0;
    double t_max = kInfinity;

    constexpr bool contains(double t) const { return t > t_min && t < t_max; }
};

// An axis-aligned bounding box; an unbounded primitive (the plane) reports infinite extents.
struct Bounds {
    Vec3 min{kInfinity, kInfinity, kInfinity};
    Vec3 max{-kInfinity, -kInfinity, -kInfinity};

    static constexpr Bounds infinite() {
        return {{-kInfinity, -kInfinity, -kInfinity}, {kInfinity, kInfinity, kInfinity}};
    }
    constexpr void expand(const Vec3& p) {
        min = component_min(min, p);
        max = component_max(max, p);
    }
    // Empty when min > max on some axis (nothing lies in it).
    constexpr bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    constexpr bool contains(const Vec3& p, double slack = 0) const {
        return p.x >= min.x - slack && p.x <= max.x + slack && p.y >= min.y - slack &&
               p.y <= max.y + slack && p.z >= min.z - slack && p.z <= max.z + slack;
    }
};

// The smallest box containing both, and the box both contain (empty when they are apart).
constexpr Bounds merged(const Bounds& a, const Bounds& b) {
    return {component_min(a.min, b.min), component_max(a.max, b.max)};
}
constexpr Bounds overlap(const Bounds& a, const Bounds& b) {
    return {component_max(a.min, b.min), component_min(a.max, b.max)};
}

}  // namespace rt
