// Where points land among the pixels of an image seen from the eye, with a bound on the
// rounding: the geometry the primary mask (primary_mask.h) projects boxes with, apart from
// its tiles.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>

#include "rt/ray.h"
#include "rt/trace.h"
#include "rt/viewer.h"

namespace rt {

// The unit roundoff of a double.
inline constexpr double kProjectionEpsilon = 0x1p-53;

inline double triple(const Vec3& a, const Vec3& b, const Vec3& c) { return dot(a, cross(b, c)); }

// A rectangle of raster positions; empty (x0 > x1) until a point is added.
struct Rectangle {
    double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
};

// Where a point lands among the pixels, seen from the eye: the inverse of the map from a
// raster position (px, py) to a direction, d0 + alpha x + beta y with d0 the eye's way to the
// image plane's centre, alpha = (2 px - xres) / xres and beta = (yres - 2 py) / yres
// (Viewer::primary_ray). A point's offset q from the eye is s d0 + a x + b y, its position
// alpha = a / s and beta = b / s, where s > 0 before the eye's plane; s, a and b are dot
// products of q with three fixed vectors.
class Projection {
  public:
    // How far (in pixels) the tracer's rounding may move a primary ray: checked.
    static constexpr double kMaxRayError = 0.25;

    explicit Projection(const Viewer& v) : eye_(v.eye), xres_(v.xres), yres_(v.yres) {
        const Vec3 centre = v.plane_centre();
        const Vec3 d0 = centre - v.eye;
        const double det = triple(d0, v.x, v.y);
        const double d0_size = length(d0), x_size = length(v.x), y_size = length(v.y);
        // |det| is at most the product of the sizes; their ratio is the frame's conditioning.
        const double conditioning = d0_size * x_size * y_size / std::fabs(det);
        if (!(conditioning <= 1e6)) return;  // nearly coplanar, or not finite
        // A primary ray's hits lie beyond the tracer's tolerance (hit_tolerance) along a unit
        // direction, whose s is 1 / |d0 + alpha x + beta y|: at s above twice this.
        nearest_ = 0.5 * kHitTolerance * (1 + max_abs_component(v.eye)) /
                   (d0_size + 2 * x_size + 2 * y_size);
        to_s_ = cross(v.x, v.y) / det;
        to_a_ = cross(v.y, d0) / det;
        to_b_ = cross(d0, v.x) / det;
        s_size_ = x_size * y_size / std::fabs(det);
        a_size_ = y_size * d0_size / std::fabs(det);
        b_size_ = d0_size * x_size / std::fabs(det);
        // A dot product with a vector computed with a relative error of about 16 roundings of
        // the conditioning, of an offset rounded once.
        offset_rounding_ = 16 * conditioning + 8;
        // A primary ray's direction as the tracer computes it, ((centre + alpha x) + beta y)
        // - eye, normalised, with |alpha| and |beta| just above 1: rounded by at most this
        // much, which moves it in the image plane (where s = 1) as an offset error would.
        const double ray_rounding =
            4 * kProjectionEpsilon *
            (length(centre) + length(v.eye) + d0_size + 4 * x_size + 4 * y_size);
        if (!(s_size_ * ray_rounding < 0.5)) return;
        const double alpha_error = 2 * (a_size_ + 2 * s_size_) * ray_rounding;
        const double beta_error = 2 * (b_size_ + 2 * s_size_) * ray_rounding;
        usable_ = alpha_error * xres_ / 2 <= kMaxRayError && beta_error * yres_ / 2 <= kMaxRayError;
    }

    bool usable() const { return usable_; }
    // A point's s (its distance before the eye's plane, in units of d0) into `s`; false
    // where it is not finite or its rounding could put it on the wrong side of nearest().
    bool depth(const Vec3& p, double& s) const {
        s = dot(p - eye_, to_s_);
        return std::isfinite(s) && s_size_ * rounding_unit(p) < nearest_ / 2;
    }
    // Primary rays meet nothing at s below this: a box is cut there (clipped).
    double nearest() const { return nearest_; }

    // Widens `r` to hold point p's projection and its rounding; false where the point is not
    // clearly before the eye's plane, or where the numbers are not finite.
    bool add(const Vec3& p, Rectangle& r) const {
        const Vec3 q = p - eye_;
        const double s = dot(q, to_s_), a = dot(q, to_a_), b = dot(q, to_b_);
        const double unit = rounding_unit(p);
        const double s_error = s_size_ * unit;
        if (!(s > 2 * s_error)) return false;
        const double alpha = a / s, beta = b / s;
        const double alpha_error = (a_size_ * unit + std::fabs(alpha) * s_error) / (s - s_error);
        const double beta_error = (b_size_ * unit + std::fabs(beta) * s_error) / (s - s_error);
        const double px = (alpha + 1) * xres_ / 2, py = (1 - beta) * yres_ / 2;
        // The division and the scaling round too, once or twice each.
        const double px_error =
            (alpha_error + 4 * kProjectionEpsilon * (1 + std::fabs(alpha))) * xres_ / 2;
        const double py_error =
            (beta_error + 4 * kProjectionEpsilon * (1 + std::fabs(beta))) * yres_ / 2;
        if (!std::isfinite(px + px_error) || !std::isfinite(py + py_error)) return false;
        r.x0 = std::min(r.x0, px - px_error);
        r.x1 = std::max(r.x1, px + px_error);
        r.y0 = std::min(r.y0, py - py_error);
        r.y1 = std::max(r.y1, py + py_error);
        return true;
    }

  private:
    // s, a and b of point p are each within this many times their size (s_size_, ...) of
    // their exact values. (Generously: a point where a box's edge is cut is rounded too.)
    double rounding_unit(const Vec3& p) const {
        return kProjectionEpsilon * (8 * (max_abs_component(p) + max_abs_component(eye_)) +
                                     offset_rounding_ * length(p - eye_));
    }

    Vec3 eye_;
    double xres_, yres_;
    Vec3 to_s_, to_a_, to_b_;
    double s_size_ = 0, a_size_ = 0, b_size_ = 0;
    double offset_rounding_ = 0;
    double nearest_ = 0;
    bool usable_ = false;
};

// The rectangle that holds the projection of the part of `box` at s >= nearest(): a
// polytope whose corners are the box's corners there and the points where its edges cross
// s = nearest, so its projection is the hull of theirs. Empty where the box lies wholly
// nearer; false where the projection fails (Projection::depth, Projection::add).
inline bool project_box(const Projection& projection, const Bounds& box, Rectangle& r) {
    Vec3 corners[8];
    double depths[8];
    for (int c = 0; c < 8; ++c) {
        corners[c] = {(c & 1) != 0 ? box.max.x : box.min.x, (c & 2) != 0 ? box.max.y : box.min.y,
                      (c & 4) != 0 ? box.max.z : box.min.z};
        if (!projection.depth(corners[c], depths[c])) return false;
    }
    const double nearest = projection.nearest();
    for (int c = 0; c < 8; ++c) {
        if (depths[c] >= nearest && !projection.add(corners[c], r)) return false;
        for (const int axis : {1, 2, 4}) {
            const int other = c | axis;  // the edge from c along this axis
            if (other == c || (depths[c] >= nearest) == (depths[other] >= nearest)) continue;
            const double f = (nearest - depths[c]) / (depths[other] - depths[c]);
            if (!projection.add(corners[c] + f * (corners[other] - corners[c]), r)) return false;
        }
    }
    return true;
}

// The tiles (of 2^shift pixels) [first, last] along one side of `pixels` that hold the
// pixels whose positions meet [lo, hi] widened by `widening`; first > last where none do.
inline std::pair<long, long> tile_span(double lo, double hi, double widening, int pixels,
                                       int shift) {
    const double first = std::max(std::floor(lo - widening), 0.0);
    const double last = std::min(std::ceil(hi + widening), static_cast<double>(pixels - 1));
    if (!(first <= last)) return {1, 0};
    return {static_cast<long>(first) >> shift, static_cast<long>(last) >> shift};
}

}  // namespace rt
