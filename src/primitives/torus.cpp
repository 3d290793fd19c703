// Torus (ID 10): centre; axis; major radius R; minor radius r. The points at distance r from
// the core circle, of radius R about the axis through the centre: the surface of the solid a
// ball of radius r sweeps as its centre runs round that circle.
//
// With h the height along the axis and rho the distance from it, the surface is the quartic
//   ((rho - R)^2 + h^2 - r^2) ((rho + R)^2 + h^2 - r^2) = 0.
// The first factor is the tube; the second vanishes only when r > R (a spindle torus), on
// the inner "lemon" where the tube overlaps itself. That lies inside the solid, so its roots
// are skipped: a spindle torus shows its outer surface only.
#include <cmath>

#include "primitives/planar.h"
#include "primitives/polynomial.h"
#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::torus {

namespace {

struct Torus {
    Vec3 centre;
    Vec3 axis;  // unit length
    double major;
    double minor;
    double reach;  // R + r: no point of the torus is farther than this from the centre
};

// A point relative to the core circle: p is taken from the centre.
struct TubeCoordinates {
    Vec3 off_axis;  // p minus its component along the axis
    double height;  // along the axis
    double radial;  // |off_axis|, the distance from the axis
};

TubeCoordinates tube_coordinates(const Torus& t, const Vec3& p) {
    const double height = dot(p, t.axis);
    const Vec3 off_axis = p - height * t.axis;
    return {off_axis, height, length(off_axis)};
}

// The tube factor and the lemon factor of the quartic at p (see the header comment).
double tube_factor(const Torus& t, const TubeCoordinates& c) {
    const double dr = c.radial - t.major;
    return dr * dr + c.height * c.height - t.minor * t.minor;
}
double lemon_factor(const Torus& t, const TubeCoordinates& c) {
    const double sr = c.radial + t.major;
    return sr * sr + c.height * c.height - t.minor * t.minor;
}

// The signed distance from p to the surface of the tube (negative inside), and its gradient
// (unit length) when p is off the core circle.
double tube_distance(const Torus& t, const Vec3& p, Vec3& gradient) {
    const TubeCoordinates c = tube_coordinates(t, p);
    // The nearest point of the core circle; on the axis every point of the circle is nearest.
    const Vec3 core = c.radial > 0 ? c.off_axis * (t.major / c.radial) : Vec3{};
    const Vec3 from_core = p - core;
    const double distance = length(from_core);
    gradient = distance > 0 ? from_core / distance : t.axis;
    return distance - t.minor;
}

// Newton steps on the distance along the ray that polish a root of the quartic: the
// distance function is evaluated directly, without the rounding of the quartic's expanded
// coefficients. One or two steps reach rounding level from the solver's root.
constexpr int kPolishSteps = 2;
// A step longer than this fraction of the minor radius is not a polish: at a grazing hit
// the distance's slope along the ray vanishes and the step is unreliable, so it is skipped.
constexpr double kMaxPolishFraction = 1e-3;
// A double's relative rounding, for the slack in comparing a rough root with the range.
constexpr double kRoundingEpsilon = 0x1p-52;

// Polishes the distance s along the ray from the centred point o (p = o + s d).
double polish(const Torus& t, const Vec3& o, const Vec3& d, double s) {
    Vec3 gradient;
    double distance = tube_distance(t, o + s * d, gradient);
    for (int step = 0; step < kPolishSteps && distance != 0; ++step) {
        const double slope = dot(gradient, d);
        const double delta = distance / slope;
        if (!(std::fabs(delta) <= kMaxPolishFraction * t.minor)) break;
        Vec3 next_gradient;
        const double next_distance = tube_distance(t, o + (s - delta) * d, next_gradient);
        if (!(std::fabs(next_distance) < std::fabs(distance))) break;
        s -= delta;
        distance = next_distance;
        gradient = next_gradient;
    }
    return s;
}

ShapeData read(SceneReader& reader) {
    const Vec3 centre = reader.vec3("torus centre");
    const Vec3 axis = reader.direction("torus axis");
    const double major = reader.positive("torus major radius");
    const double minor = reader.positive("torus minor radius");
    return reader.shape_data(Torus{centre, axis, major, minor, major + minor});
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    const auto& t = *static_cast<const Torus*>(shape);
    const Vec3& d = ray.direction;
    // Move the origin along the ray to the point nearest the centre and measure from there:
    // every hit then lies within reach of it, so the quartic's roots are of the torus's size
    // however far away the ray started (a distant origin would otherwise swamp the roots in
    // the rounding of huge coefficients). The offset is added back at the end.
    const Vec3 from_centre = ray.origin - t.centre;
    const double offset = -dot(from_centre, d);
    if (offset - t.reach >= range.t_max || offset + t.reach <= range.t_min) return false;
    const Vec3 nearest = from_centre + offset * d;
    const double nearest_squared = length_squared(nearest);
    if (nearest_squared > t.reach * t.reach) return false;  // misses the bounding sphere

    // The quartic in s, the distance from the nearest point in units of reach, so that its
    // coefficients are of order 1 whatever the torus's size. With p = o + s d:
    //   (|p|^2 + R^2 - r^2)^2 - 4 R^2 rho^2 = 0,   rho^2 = |p|^2 - (p.n)^2.
    const double unit = 1 / t.reach;
    const Vec3 o = nearest * unit;
    const double big = t.major * unit, small = t.minor * unit;
    const double e = dot(o, d);  // zero but for rounding
    const double oo = nearest_squared * unit * unit;
    const double on = dot(o, t.axis), dn = dot(d, t.axis);
    const double k = oo + (big - small) * (big + small);
    const double four_big2 = 4 * big * big;
    // The constant term is the quartic at o, taken as the product of its factors so that its
    // sign is right near the surface.
    const Torus scaled{{}, t.axis, big, small, 1};
    const TubeCoordinates at_o = tube_coordinates(scaled, o);
    const double coefficients[5] = {
        tube_factor(scaled, at_o) * lemon_factor(scaled, at_o),
        4 * e * k - 2 * four_big2 * (e - on * dn),
        4 * e * e + 2 * k - four_big2 * (1 - dn * dn),
        4 * e,
        1,
    };
    const Roots roots = solve_polynomial(coefficients);

    // A root straight from the quartic is only as good as its rounding allows (near a
    // double root, as on a spindle torus whose tube is millions of times its major radius, a
    // large part of the minor radius); the polished root is the hit. Polishing moves a root
    // by at most kPolishSteps * kMaxPolishFraction * minor, so only a rough root beyond the
    // range by more than that (and rounding) is passed over unpolished, and the hit is the
    // nearest polished root in range. Deciding on rough roots made the answer depend on the
    // range the caller gave: the hierarchy, which narrows it to the nearest hit so far, and
    // the linear scan then saw different tori in front.
    const double margin = 2 * kPolishSteps * kMaxPolishFraction * t.minor +
                          8 * kRoundingEpsilon * (std::fabs(offset) + t.reach);
    const bool spindle = t.minor >= t.major;
    bool found = false;
    double nearest_hit = range.t_max;
    for (double s : roots) {
        const double rough = offset + s * t.reach;
        if (rough <= range.t_min - margin) continue;
        if (rough >= nearest_hit + margin) break;  // the roots ascend
        // Roots on the lemon of a spindle torus are inside the solid: not a surface.
        if (spindle) {
            const TubeCoordinates c = tube_coordinates(scaled, o + s * d);
            if (std::fabs(lemon_factor(scaled, c)) < std::fabs(tube_factor(scaled, c))) continue;
        }
        const double polished = offset + polish(t, nearest, d, s * t.reach);
        if (!(polished > range.t_min) || !(polished < nearest_hit)) continue;
        nearest_hit = polished;
        found = true;
    }
    if (found) hit = {nearest_hit, 0};
    return found;
}

Vec3 normal(const void* shape, const Vec3& point, const Hit&) {
    const auto& t = *static_cast<const Torus*>(shape);
    // Away from the nearest point of the core circle. On the axis (the cusps of a horn or
    // spindle torus, where there is no tangent plane) that is along the axis.
    Vec3 gradient;
    tube_distance(t, point - t.centre, gradient);
    return gradient;
}

Bounds bounds(const void* shape) {
    const auto& t = *static_cast<const Torus*>(shape);
    // The core circle's box, grown by the tube's radius on every side.
    Bounds b = disk_bounds(t.centre, t.axis, t.major);
    const Vec3 r{t.minor, t.minor, t.minor};
    return {b.min - r, b.max + r};
}

bool inside(const void* shape, const Vec3& point) {
    const auto& t = *static_cast<const Torus*>(shape);
    return tube_factor(t, tube_coordinates(t, point - t.centre)) < 0;
}

}  // namespace

extern const PrimitiveFunctions functions{
    .read = read, .intersect = intersect, .normal = normal, .bounds = bounds, .inside = inside};

}  // namespace rt::torus
