// What the flat primitives share: the plane n.x = D that carries them, and coordinates
// (alpha, beta) of a point in the plane along two edge vectors.
#pragma once

#include <cmath>
#include <optional>

#include "rt/primitive.h"

namespace rt {

struct Plane {
    Vec3 normal;    // unit length
    double offset;  // D in n.x = D

    // The distance to the plane along a ray, or nothing for a ray parallel to it (as the
    // original: "the line is along the plane, and no intersection is returned") or a hit
    // outside the range.
    std::optional<double> distance(const Ray& ray, Interval range) const {
        const double facing = dot(normal, ray.direction);
        if (facing == 0) return std::nullopt;
        const double t = (offset - dot(normal, ray.origin)) / facing;
        if (!range.contains(t)) return std::nullopt;
        return t;
    }
};

// Coordinates of points v0 + alpha a + beta b (section 2.5 of the original). Solving the 2x2
// system once at read time leaves two dot products per test.
struct EdgeFrame {
    Vec3 origin;
    Vec3 to_alpha;  // alpha = to_alpha . (x - origin)
    Vec3 to_beta;   // beta = to_beta . (x - origin)

    // Returns nothing when a and b are parallel (a zero-area shape).
    static std::optional<EdgeFrame> make(const Vec3& origin, const Vec3& a, const Vec3& b) {
        const double aa = dot(a, a), ab = dot(a, b), bb = dot(b, b);
        const double det = aa * bb - ab * ab;
        // Relative test: det is |a x b|^2, so compare with |a|^2 |b|^2.
        if (!(det > 1e-24 * aa * bb)) return std::nullopt;
        return EdgeFrame{origin, (bb * a - ab * b) / det, (aa * b - ab * a) / det};
    }
    double alpha(const Vec3& x) const { return dot(to_alpha, x - origin); }
    double beta(const Vec3& x) const { return dot(to_beta, x - origin); }
};

// The bounds of a disk of a given radius in the plane with unit normal n: along each axis
// the disk reaches r sqrt(1 - n_axis^2) from its centre.
inline Bounds disk_bounds(const Vec3& centre, const Vec3& n, double radius) {
    auto reach = [&](double component) {
        const double s = 1 - component * component;
        return radius * std::sqrt(s > 0 ? s : 0);
    };
    const Vec3 r{reach(n.x), reach(n.y), reach(n.z)};
    return {centre - r, centre + r};
}

// A flat shape spanned by two edges from a vertex: the triangle and the parallelogram differ
// only in which (alpha, beta) they keep.
struct EdgePatch {
    Plane plane;
    EdgeFrame frame;
    Bounds box;

    struct Point {
        double t, alpha, beta;
    };

    static std::optional<EdgePatch> make(const Vec3& v0, const Vec3& a, const Vec3& b,
                                         const Bounds& box) {
        const auto frame = EdgeFrame::make(v0, a, b);
        if (!frame) return std::nullopt;
        const Vec3 n = normalized(cross(a, b));
        return EdgePatch{{n, dot(n, v0)}, *frame, box};
    }

    std::optional<Point> locate(const Ray& ray, Interval range) const {
        const auto t = plane.distance(ray, range);
        if (!t) return std::nullopt;
        const Vec3 x = ray.at(*t);
        return Point{*t, frame.alpha(x), frame.beta(x)};
    }
};

}  // namespace rt

namespace rt {

// The flat round shapes: a disk is a ring whose hole has radius 0.
struct Ring {
    Plane plane;
    Vec3 centre;
    double outer;
    double outer_squared;
    double inner_squared;

    static Ring make(const Vec3& centre, const Vec3& unit_normal, double outer, double inner) {
        return {
            {unit_normal, dot(unit_normal, centre)}, centre, outer, outer * outer, inner * inner};
    }
    bool intersect(const Ray& ray, Interval range, Hit& hit) const {
        const auto t = plane.distance(ray, range);
        if (!t) return false;
        const double r2 = length_squared(ray.at(*t) - centre);
        if (r2 > outer_squared || r2 < inner_squared) return false;
        hit = {*t, 0};
        return true;
    }
    Bounds bounds() const { return disk_bounds(centre, plane.normal, outer); }
};

}  // namespace rt
