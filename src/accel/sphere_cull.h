// A leaf's spheres culled eight at a time in float, ahead of their exact tests, for the object
// hierarchies where that pays: those whose rays meet many spheres in large leaves, which is
// what spheres that overlap heavily make (ObjectIndex::cull_pays; docs/performance.md,
// "Overlapping spheres culled eight at a time"). The cull only ever drops a sphere that the
// exact double test (sphere_test.h) would reject, so every hit, and every image, is what it
// is without the cull.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "accel/bvh.h"
#include "rt/primitive.h"
#include "rt/ray.h"

namespace rt {

class SphereCull {
  public:
    static constexpr int kLanes = 8;

    // A ray prepared for the cull: its origin and direction rounded to floats, and what their
    // magnitude adds to every bound.
    struct Ray8 {
        float origin[3], direction[3];
        float margin;
        bool behind;  // t_min >= 0: a sphere wholly behind the origin can be dropped
    };

    SphereCull() = default;
    // Room for `count` places in leaf order, each kept always until set(). Eight more at the
    // end, so that a leaf's eight lanes can be loaded wherever it starts.
    explicit SphereCull(std::size_t count) : stride_(count + kLanes), rows_(kRows * stride_, 0.0f) {
        std::fill_n(rows_.begin() + kReach * static_cast<std::ptrdiff_t>(stride_), stride_,
                    HUGE_VALF);
    }
    bool empty() const { return rows_.empty(); }

    // Place i holds the sphere s. One beyond kLargest is kept always.
    void set(std::size_t i, const SphereParameters& s) {
        const double r = std::sqrt(s.radius_squared);
        const double c = max_abs_component(s.centre);
        if (!(c <= kLargest && r <= kLargest)) return;
        row(kX)[i] = static_cast<float>(s.centre.x);
        row(kY)[i] = static_cast<float>(s.centre.y);
        row(kZ)[i] = static_cast<float>(s.centre.z);
        const double slack = kRelative * (c + r) + kFloor;
        row(kReach)[i] = float_up(r + slack);
        row(kSlack)[i] = float_up(slack);
    }

    // A ray whose origin is beyond kLargest, or whose direction is not of unit length (the
    // exact test's own premise), gets bounds that keep every sphere.
    static Ray8 prepare(const Ray& ray, double t_min) {
        const double o = max_abs_component(ray.origin);
        const bool usable =
            o <= kLargest && std::fabs(length_squared(ray.direction) - 1) <= kUnitTolerance;
        Ray8 r{};
        for (int k = 0; k < 3; ++k) {
            r.origin[k] = usable ? static_cast<float>(ray.origin[k]) : 0.0f;
            r.direction[k] = usable ? static_cast<float>(ray.direction[k]) : 0.0f;
        }
        r.margin = usable ? float_up(kRelative * o) : HUGE_VALF;
        r.behind = t_min >= 0;
        return r;
    }

    // Bit k set for each place first + k (k < count <= 8) whose sphere the ray may cross in
    // (t_min, t_max): every sphere that is not surely missed (the ray's distance from its
    // centre beyond its radius), surely wholly behind the origin (the centre behind it, the
    // origin outside), or surely wholly beyond t_max (the centre's distance along the ray
    // less the radius past it). Each "surely" holds against the float arithmetic's every
    // rounding: a bound is widened by 2^-14 of the magnitudes involved, where the roundings
    // of these few operations come to under 2^-20 (docs/performance.md has the argument).
    // Avx2: whether the caller is compiled for AVX2 (sign_bits).
    template <bool Avx2>
    [[gnu::always_inline]] unsigned keep(const Ray8& ray, std::uint32_t first, std::uint32_t count,
                                         double t_max) const {
        using Floats = LaneVectors<kLanes>::Floats;
        using Ints = LaneVectors<kLanes>::Ints;
        // Rounded to the nearest float, and above t_max all the same: the widening exceeds
        // that rounding, and the floor keeps tiny distances above it. A negative t_max (an
        // empty range) culls nothing beyond.
        const float limit = t_max >= 0 && t_max < kLargest
                                ? static_cast<float>(t_max * (1 + 0x1p-20) + kFloor)
                                : HUGE_VALF;
        Floats x, y, z, reach, slack;
        std::memcpy(&x, at(kX, first), sizeof x);
        std::memcpy(&y, at(kY, first), sizeof y);
        std::memcpy(&z, at(kZ, first), sizeof z);
        std::memcpy(&reach, at(kReach, first), sizeof reach);
        std::memcpy(&slack, at(kSlack, first), sizeof slack);
        // From the origin to the centre, the centre's distance along the ray, and the rest.
        x -= ray.origin[0];
        y -= ray.origin[1];
        z -= ray.origin[2];
        const Floats along = x * ray.direction[0] + y * ray.direction[1] + z * ray.direction[2];
        const Floats px = x - along * ray.direction[0];
        const Floats py = y - along * ray.direction[1];
        const Floats pz = z - along * ray.direction[2];
        reach += ray.margin;
        slack += ray.margin;
        const Floats reach2 = reach * reach;
        const Ints missed = px * px + py * py + pz * pz > reach2;
        const Ints behind =
            ray.behind ? (along < -slack) & (x * x + y * y + z * z > reach2) : Ints{};
        const Ints beyond = along - reach - slack > limit;
        return ~sign_bits<kLanes, Avx2>(missed | behind | beyond) & ((1u << count) - 1);
    }

  private:
    enum Row { kX, kY, kZ, kReach, kSlack, kRows };
    // Coordinates and distances beyond this are not culled: squares stay far inside a float.
    static constexpr double kLargest = 1e15;
    static constexpr double kRelative = 0x1p-14;
    // Bounds at least this: their squares stay normal floats, so no subnormal rounding can
    // turn a comparison.
    static constexpr double kFloor = 1e-18;
    // A direction this close to unit length: its error is far inside the widening.
    static constexpr double kUnitTolerance = 1e-6;

    // The float nearest v, moved up one step where that is below v (v >= 0, finite).
    static float float_up(double v) {
        const auto f = static_cast<float>(v);
        return static_cast<double>(f) < v ? std::nextafter(f, HUGE_VALF) : f;
    }
    float* row(Row r) { return rows_.data() + static_cast<std::size_t>(r) * stride_; }
    const float* at(Row r, std::uint32_t first) const {
        return rows_.data() + static_cast<std::size_t>(r) * stride_ + first;
    }

    std::size_t stride_ = 0;
    std::vector<float> rows_;
};

}  // namespace rt
