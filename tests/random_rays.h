// Helpers for the tests that fire seeded random rays at one primitive and compare what it
// reports with a closed form worked out in the test: the rays that recur, what a closed form
// answers, and the comparison every such test makes before its primitive's own checks.
#pragma once

#include <cmath>
#include <optional>

#include "check.h"
#include "scene_util.h"

namespace rt_test {

// A ray from anywhere in the box of half-size 10 about the origin, in any direction.
inline rt::Ray any_ray(Random& random) {
    const rt::Vec3 origin = random.in_box(10);
    return {origin, random.unit_vector()};
}

// A ray for a ball of radius r about c: every third starts inside it (within 0.55 r of c), the
// others anywhere in the box of half-size 10; three in four aim within 1.5 r of c, the rest go
// in any direction. `i` is the ray's number in its test.
inline rt::Ray ray_at_ball(Random& random, const rt::Vec3& c, double r, int i) {
    const rt::Vec3 o = i % 3 == 0 ? c + random.in_box(r * 0.55) : random.in_box(10);
    const rt::Vec3 aim = c + random.in_box(r * 1.5);
    return {o, i % 4 ? normalized(aim - o) : random.unit_vector()};
}

// What a closed form says a ray meets.
struct ClosedForm {
    std::optional<double> t;      // the distance to the first hit, or nothing
    bool ambiguous = false;       // the answer hangs on rounding: either is right
    bool nearer_clipped = false;  // a nearer crossing lay outside the extent

    // Takes the crossings of a surface cut to the extent [start, finish] nearest first: one at
    // distance t whose extent coordinate is h. A crossing within rounding of a rim makes the
    // answer ambiguous; the first one ahead of the origin within the extent is the hit.
    template <typename Real>
    void crossing(Real distance, double h, double start, double finish) {
        if (std::fabs(h - start) < 1e-7 || std::fabs(h - finish) < 1e-7) ambiguous = true;
        if (distance <= 1e-6 || t) return;
        if (h >= start && h <= finish)
            t = static_cast<double>(distance);
        else
            nearer_clipped = true;
    }
};

// How the rays of a test fared against the closed form.
struct RayCounts {
    int hits = 0;     // both hit
    int misses = 0;   // one missed (a failure unless both did)
    int skipped = 0;  // ambiguous, not compared
};

struct MatchedHit {
    rt::Hit hit;
    rt::Vec3 point;  // where the ray meets the shape
};

// Compares the shape's first hit along `ray` with the closed form's. A ray the closed form
// calls ambiguous is skipped; otherwise both hit or neither, and where both do, at the same
// distance within relative_tolerance * (1 + t), divided by the cosine of incidence where the
// ray meets a flat surface at a slant. Returns the hit and its point where both hit, for the
// primitive's own checks.
inline std::optional<MatchedHit> compare_first_hit(const rt::Shape& shape, const rt::Ray& ray,
                                                   const ClosedForm& expected,
                                                   double relative_tolerance, RayCounts& counts,
                                                   double cos_incidence = 1) {
    if (expected.ambiguous) {
        ++counts.skipped;
        return std::nullopt;
    }
    const auto hit = first_hit(shape, ray);
    CHECK_EQ(hit.has_value(), expected.t.has_value());
    if (!hit || !expected.t) {
        ++counts.misses;
        return std::nullopt;
    }
    ++counts.hits;
    CHECK_NEAR(hit->t, *expected.t, relative_tolerance * (1 + *expected.t) / cos_incidence);
    return MatchedHit{*hit, ray.at(hit->t)};
}

}  // namespace rt_test
