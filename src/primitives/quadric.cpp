// Quadric (ID 13): A B C D E F G H I J; clip box min; clip box max. The surface
//   f(x) = Ax² + By² + Cz² + 2Dxy + 2Exz + 2Fyz + 2Gx + 2Hy + 2Iz + J = 0,
// kept where it lies in the clip box. Its outward normal is ∇f/|∇f| and its solid (for CSG)
// is f < 0, which the box does not clip.
//
// In matrix form f(x) = xᵀQx + 2g·x + J. rt stores f about a point p0 at the centre of the
// visible surface's bounds, f(p0 + y) = yᵀQy + 2(Qp0 + g)·y + f(p0), so the large terms of a
// quadric far from the world's origin cancel once, when the scene is read, not on every ray.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::quadric {

namespace {

struct Symmetric {
    double xx, yy, zz, xy, xz, yz;

    constexpr Vec3 operator*(const Vec3& v) const {
        return {xx * v.x + xy * v.y + xz * v.z, xy * v.x + yy * v.y + yz * v.z,
                xz * v.x + yz * v.y + zz * v.z};
    }
};

struct Quadric {
    Symmetric q;
    Vec3 linear;      // Qp0 + g: half the gradient at p0
    double constant;  // f(p0)
    Vec3 p0;
    Bounds clip;
    Bounds bounds;     // of the visible surface
    bool has_visible;  // false when no point of the surface can lie in the clip box
    Bounds solid;      // of the solid f < 0
};

// A hit's computed point is off by rounding; the clip test allows this much, relative to the
// size of the ray's coordinates, so a surface lying in a face of the box (x² − 1 = 0 with the
// box's x from −1 to 1) shows whole, not speckled.
constexpr double kClipSlack = 1e-12;
// Q is treated as definite (the surface bounded, an ellipsoid) only when its smallest
// eigenvalue is at least this fraction of its largest; a nearly singular Q (a long ellipsoid
// written with rounding next to a cylinder) keeps the clip box as its bounds.
constexpr double kDefiniteMargin = 1e-9;
// The ellipsoid's computed extent is widened by this fraction of its size and distance from
// the origin, for rounding (the hierarchy widens every box by 1e-9 more).
constexpr double kExtentPad = 1e-10;

// Double-double arithmetic: a value as the unevaluated sum hi + lo of two doubles (about 106
// bits), built from error-free transformations on std::fma, which rounds alike on every IEEE
// target. (long double would not: it is 80-bit x87 on x86-64 and 128-bit IEEE on arm64, and
// so gave different images of a quadric far from the origin.) Values that overflow a double
// keep their infinite hi and a lo of 0, so no NaN arises from the error terms.
struct Wide {
    double hi = 0;
    double lo = 0;

    Wide() = default;
    Wide(double v) : hi(v) {}  // NOLINT: a double is a Wide exactly
    Wide(double h, double l) : hi(h), lo(l) {}
    double value() const { return std::isfinite(hi) ? hi + lo : hi; }
};

// hi + lo exactly, with |a| >= |b| or a == 0.
Wide quick_two_sum(double a, double b) {
    const double s = a + b;
    if (!std::isfinite(s)) return {s, 0};
    return {s, b - (s - a)};
}

Wide two_sum(double a, double b) {
    const double s = a + b;
    if (!std::isfinite(s)) return {s, 0};
    const double bb = s - a;
    return {s, (a - (s - bb)) + (b - bb)};
}

Wide operator+(const Wide& a, const Wide& b) {
    Wide s = two_sum(a.hi, b.hi);
    const Wide t = two_sum(a.lo, b.lo);
    s = quick_two_sum(s.hi, s.lo + t.hi);
    return quick_two_sum(s.hi, s.lo + t.lo);
}
Wide operator-(const Wide& a) { return {-a.hi, -a.lo}; }
Wide operator-(const Wide& a, const Wide& b) { return a + -b; }

Wide operator*(const Wide& a, const Wide& b) {
    const double p = a.hi * b.hi;
    if (!std::isfinite(p)) return {p, 0};
    const double e = std::fma(a.hi, b.hi, -p) + (a.hi * b.lo + a.lo * b.hi);
    return quick_two_sum(p, e);
}

Wide operator/(const Wide& a, const Wide& b) {
    const double q1 = a.hi / b.hi;
    if (!std::isfinite(q1)) return {q1, 0};
    const Wide r = a - b * q1;
    const double q2 = r.hi / b.hi;
    const Wide r2 = r - b * q2;
    return quick_two_sum(q1, q2) + r2.hi / b.hi;
}

// The square root of a >= 0: the double root, then one Newton correction.
Wide sqrt(const Wide& a) {
    if (!(a.hi > 0)) return std::sqrt(a.hi);  // 0, or NaN for a negative value
    const double x = std::sqrt(a.hi);
    if (!std::isfinite(x)) return {x, 0};
    return two_sum(x, (a - Wide(x) * x).hi / (2 * x));
}

bool operator<(const Wide& a, const Wide& b) {
    return a.hi < b.hi || (a.hi == b.hi && a.lo < b.lo);
}
bool operator>(const Wide& a, const Wide& b) { return b < a; }

Vec3 with_component(Vec3 v, int axis, double value) {
    (axis == 0 ? v.x : axis == 1 ? v.y : v.z) = value;
    return v;
}

double f_at(const Quadric& s, const Vec3& y) { return dot(y, s.q * y + 2 * s.linear) + s.constant; }

// The quadratic a s² + 2b s + c = 0 that f takes along a ray, in s, the distance from the
// ray's point nearest p0 (t = offset + s). Measuring from there keeps c of the surface's
// size however far away the ray starts.
struct AlongRay {
    double offset;
    double a, b, c;
};

AlongRay along_ray(const Quadric& s, const Ray& ray) {
    const Vec3& d = ray.direction;
    const Vec3 from_p0 = ray.origin - s.p0;
    const double offset = -dot(from_p0, d);
    const Vec3 nearest = from_p0 + offset * d;
    const Vec3 qd = s.q * d;
    return {offset, dot(d, qd), dot(qd, nearest) + dot(d, s.linear), f_at(s, nearest)};
}

// The real roots of a s² + 2b s + c = 0 in ascending order. `touching`: one double root (a
// tangent ray), which touches the surface without crossing it.
struct Roots {
    std::array<double, 2> s{};
    int count = 0;
    bool touching = false;
};

Roots solve(double a, double b, double c) {
    // b² − ac with one rounding (Kahan's fused multiply-add trick): near a tangent the two
    // products nearly cancel.
    const double ac = a * c;
    const double discriminant = std::fma(b, b, -ac) + std::fma(-a, c, ac);
    if (discriminant < 0) return {};
    // Along an asymptote of a cone or hyperboloid, or the axis of a paraboloid: linear.
    if (a == 0) {
        if (b == 0) return {};  // the ray misses, or runs inside the surface: no hit either way
        return {{-c / (2 * b), 0}, 1, false};
    }
    // The root of larger magnitude from q, the other as c / q: no cancellation.
    const double q = -(b + std::copysign(std::sqrt(discriminant), b));
    if (discriminant == 0 || q == 0) return {{-b / a, 0}, 1, true};
    const double first = q / a, second = c / q;
    return first < second ? Roots{{first, second}, 2, false} : Roots{{second, first}, 2, false};
}

bool visible_at(const Quadric& s, const Ray& ray, double t) {
    const double slack = kClipSlack * (max_abs_component(ray.origin) + std::fabs(t));
    return s.clip.contains(ray.at(t), slack);
}

// The box of an ellipsoid: when Q is definite, the surface f = 0 is bounded, and so is one
// side of it. Worked out in double-double: for an ellipsoid far from the origin, g·c and J
// nearly cancel. Q, g and J are first scaled by a power of two (exactly) so that Q's largest
// entry is near 1, which changes neither the surface nor any ratio below, and keeps the
// products of Q's entries from overflowing.
struct Extent {
    bool definite = false;
    bool solid_inside = false;  // f < 0 is the ellipsoid's interior (Q positive definite)
    bool empty = false;         // f = 0 has no real points
    Bounds box;                 // the surface's box, when definite and not empty
    Vec3 centre;
};

Extent ellipsoid_extent(const Symmetric& unscaled_q, const Vec3& unscaled_g, double unscaled_j) {
    Extent extent;
    const double largest =
        std::max({std::fabs(unscaled_q.xx), std::fabs(unscaled_q.yy), std::fabs(unscaled_q.zz),
                  std::fabs(unscaled_q.xy), std::fabs(unscaled_q.xz), std::fabs(unscaled_q.yz)});
    if (!(largest > 0)) return extent;
    const int exponent = std::ilogb(largest);
    const auto scaled = [&](double v) { return std::scalbn(v, -exponent); };
    const Wide xx = scaled(unscaled_q.xx), yy = scaled(unscaled_q.yy), zz = scaled(unscaled_q.zz),
               xy = scaled(unscaled_q.xy), xz = scaled(unscaled_q.xz), yz = scaled(unscaled_q.yz);
    const Wide gx = scaled(unscaled_g.x), gy = scaled(unscaled_g.y), gz = scaled(unscaled_g.z);
    const Wide j = scaled(unscaled_j);
    // The adjugate of Q (Q⁻¹ = adjugate / det).
    const Wide adj_xx = yy * zz - yz * yz, adj_yy = xx * zz - xz * xz, adj_zz = xx * yy - xy * xy;
    const Wide adj_xy = xz * yz - xy * zz, adj_xz = xy * yz - yy * xz, adj_yz = xy * xz - xx * yz;
    const Wide det = xx * adj_xx + xy * adj_xy + xz * adj_xz;
    // Sylvester's criterion; then det / |Q|³ bounds the ratio of the extreme eigenvalues.
    const double sign = xx.hi > 0 ? 1 : -1;
    const Wide norm = sqrt(xx * xx + yy * yy + zz * zz + Wide(2) * (xy * xy + xz * xz + yz * yz));
    extent.definite = xx.hi != 0 && adj_zz > Wide(0) &&
                      Wide(sign) * det > Wide(kDefiniteMargin) * norm * norm * norm;
    if (!extent.definite) return extent;
    extent.solid_inside = sign > 0;
    // The centre c = −Q⁻¹g, where f(x) = (x−c)ᵀQ(x−c) + f(c) and f(c) = g·c + J.
    const Wide cx = -(adj_xx * gx + adj_xy * gy + adj_xz * gz) / det;
    const Wide cy = -(adj_xy * gx + adj_yy * gy + adj_yz * gz) / det;
    const Wide cz = -(adj_xz * gx + adj_yz * gy + adj_zz * gz) / det;
    // sign·Q is positive definite, so the surface is (x−c)ᵀ(sign·Q)(x−c) = k.
    const Wide k = -(Wide(sign) * (gx * cx + gy * cy + gz * cz + j));
    extent.centre = {cx.value(), cy.value(), cz.value()};
    // A centre or level beyond a double's range: the clip box bounds the surface instead.
    if (!std::isfinite(extent.centre.x) || !std::isfinite(extent.centre.y) ||
        !std::isfinite(extent.centre.z) || !std::isfinite(k.hi)) {
        extent.definite = false;
        return extent;
    }
    extent.empty = k < Wide(0);
    if (extent.empty) return extent;
    const Wide diagonal[3] = {adj_xx, adj_yy, adj_zz};
    for (int axis = 0; axis < 3; ++axis) {
        const double half = sqrt(k * Wide(sign) * diagonal[axis] / det).value();
        const double pad = kExtentPad * (half + std::fabs(extent.centre[axis]));
        extent.box.min = with_component(extent.box.min, axis, extent.centre[axis] - half - pad);
        extent.box.max = with_component(extent.box.max, axis, extent.centre[axis] + half + pad);
    }
    return extent;
}

// The box of the surface inside the clip box: the clip box, cut down to the ellipsoid's
// extent when Q is definite. has_visible is false when nothing is left.
Bounds visible_bounds(const Extent& extent, const Bounds& clip, bool& has_visible) {
    has_visible = true;
    if (!extent.definite) return clip;
    if (extent.empty) {
        has_visible = false;
        return {extent.centre, extent.centre};
    }
    const Bounds cut = overlap(clip, extent.box);
    if (cut.empty()) {
        has_visible = false;
        return {clip.min, clip.min};
    }
    return cut;
}

// The box of the solid f < 0, which the clip box does not cut: the ellipsoid's when f < 0 is
// its interior (a point when that is empty), and unbounded otherwise.
Bounds solid_box(const Extent& extent) {
    if (!extent.definite || !extent.solid_inside) return Bounds::infinite();
    if (extent.empty) return {extent.centre, extent.centre};
    return extent.box;
}

ShapeData read(SceneReader& reader) {
    const Location first = reader.next_location();
    std::array<double, 10> k{};
    static constexpr std::array<const char*, 10> kNames{"A", "B", "C", "D", "E",
                                                        "F", "G", "H", "I", "J"};
    for (std::size_t i = 0; i < k.size(); ++i)
        k[i] = reader.number(std::string("quadric coefficient ") + kNames[i]);
    bool all_zero = true;
    for (std::size_t i = 0; i < 9; ++i) all_zero = all_zero && k[i] == 0;
    if (all_zero)
        reader.fail(first,
                    "quadric coefficients A to I must not all be zero (the equation would be "
                    "the constant J = 0)");
    const Vec3 clip_min = reader.vec3("quadric clip box min");
    const Location max_at = reader.next_location();
    const Vec3 clip_max = reader.vec3("quadric clip box max");
    static constexpr std::array<const char*, 3> kAxisNames{"x", "y", "z"};
    for (int axis = 0; axis < 3; ++axis)
        if (clip_min[axis] > clip_max[axis])
            reader.fail(max_at, std::string("quadric clip box max must be >= its min in every "
                                            "component, got ") +
                                    kAxisNames[static_cast<std::size_t>(axis)] + " max " +
                                    format_number(clip_max[axis]) + " < min " +
                                    format_number(clip_min[axis]));

    const Symmetric q{k[0], k[1], k[2], k[3], k[4], k[5]};
    const Vec3 g{k[6], k[7], k[8]};
    const Bounds clip{clip_min, clip_max};
    const Extent extent = ellipsoid_extent(q, g, k[9]);
    bool has_visible = true;
    const Bounds bounds = visible_bounds(extent, clip, has_visible);
    const Vec3 p0 = 0.5 * (bounds.min + bounds.max);
    // Qp0 + g and f(p0) = p0·(Qp0 + 2g) + J in double-double: for a quadric far from the
    // origin their terms nearly cancel.
    const Wide px = p0.x, py = p0.y, pz = p0.z;
    const Wide hx = Wide(q.xx) * px + Wide(q.xy) * py + Wide(q.xz) * pz + g.x;
    const Wide hy = Wide(q.xy) * px + Wide(q.yy) * py + Wide(q.yz) * pz + g.y;
    const Wide hz = Wide(q.xz) * px + Wide(q.yz) * py + Wide(q.zz) * pz + g.z;
    const Wide value = px * (hx + g.x) + py * (hy + g.y) + pz * (hz + g.z) + k[9];
    const Vec3 linear{hx.value(), hy.value(), hz.value()};
    return reader.shape_data(
        Quadric{q, linear, value.value(), p0, clip, bounds, has_visible, solid_box(extent)});
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    const auto& s = *static_cast<const Quadric*>(shape);
    if (!s.has_visible) return false;
    const AlongRay along = along_ray(s, ray);
    const Roots roots = solve(along.a, along.b, along.c);
    for (int i = 0; i < roots.count; ++i) {
        const double t = along.offset + roots.s[static_cast<std::size_t>(i)];
        if (!(t > range.t_min)) continue;  // NaN too (a ray with no direction)
        if (t >= range.t_max) return false;
        if (!visible_at(s, ray, t)) continue;  // clipped: the far root may still show
        hit = {t, 0};
        return true;
    }
    return false;
}

bool cross(const void* shape, const Ray& ray, Interval range, Crossing& crossing) {
    const auto& s = *static_cast<const Quadric*>(shape);
    const AlongRay along = along_ray(s, ray);
    const Roots roots = solve(along.a, along.b, along.c);
    if (roots.touching) return false;  // a tangent ray stays on one side
    for (int i = 0; i < roots.count; ++i) {
        const double t = along.offset + roots.s[static_cast<std::size_t>(i)];
        if (!(t > range.t_min)) continue;  // NaN too (a ray with no direction)
        if (t >= range.t_max) return false;
        // The sign of the quadratic's slope at the root, read from its shape rather than
        // from a rounded gradient, so crossings alternate in and out along the ray.
        const bool entering = roots.count == 1 ? along.b < 0 : (i == 0) == (along.a > 0);
        crossing = {Hit{t, 0}, entering, visible_at(s, ray, t)};
        return true;
    }
    return false;
}

Vec3 normal(const void* shape, const Vec3& point, const Hit&) {
    const auto& s = *static_cast<const Quadric*>(shape);
    const Vec3 half_gradient = s.q * (point - s.p0) + s.linear;
    const double size = length(half_gradient);
    // At a singular point (a cone's apex, the line where a plane pair's planes meet) the
    // gradient vanishes and no direction is better than another.
    if (!(size > 0)) return {0, 0, 1};
    return half_gradient / size;
}

Bounds bounds(const void* shape) { return static_cast<const Quadric*>(shape)->bounds; }

Bounds solid_bounds(const void* shape) { return static_cast<const Quadric*>(shape)->solid; }

bool inside(const void* shape, const Vec3& point) {
    const auto& s = *static_cast<const Quadric*>(shape);
    return f_at(s, point - s.p0) < 0;
}

}  // namespace

// Its solid f < 0 is not clipped by its box, so it reports invisible crossings too.
extern const PrimitiveFunctions functions{.read = read,
                                          .intersect = intersect,
                                          .normal = normal,
                                          .bounds = bounds,
                                          .inside = inside,
                                          .cross = cross,
                                          .solid_bounds = solid_bounds};

}  // namespace rt::quadric
