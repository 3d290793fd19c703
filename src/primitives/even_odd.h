// The polygon's even-odd rule (polygon.cpp): the crossing test of one edge, and the box
// outside which no point is inside, which decides most points before any edge's division
// without changing one answer (docs/performance.md, "Polygons with many vertices", "A box
// before the edges").
#pragma once

#include <cfloat>
#include <cmath>
#include <span>

namespace rt::polygon {

struct Point2 {
    double u, v;
};

// Whether a ray from p along +u crosses the edge from a to b. Each edge is taken as
// half-open in v, so a ray through a vertex counts the two edges there once between them.
// This arithmetic is the polygon's definition: every image depends on its roundings.
inline bool crosses(const Point2& a, const Point2& b, Point2 p) {
    if ((a.v > p.v) == (b.v > p.v)) return false;
    const double crossing_u = a.u + (p.v - a.v) * (b.u - a.u) / (b.v - a.v);
    return p.u < crossing_u;
}

// How far outside [min(a.u, b.u), max(a.u, b.u)] the crossing_u that `crosses` computes
// can fall, with room to spare, for an outline whose largest |u| and |v| are given and
// whose edges rise, where they rise at all, by at least `smallest_rise` in v (as the
// rounded b.v - a.v). Where an edge straddles p.v, the rounded p.v - a.v lies between 0
// and the rounded b.v - a.v (rounding is monotonic), so their quotient is in [0, 1], and
// the three roundings after it put crossing_u within 4 * 2^-53 * (|a.u| + |b.u|) of the
// edge's u-range: 2^-46 * largest_u is sixteen times that, and leaves room for the
// rounding of the box's own ends. DBL_MIN covers a rounding in the subnormals, and
// 2^-1068 / smallest_rise a subnormal product's (at most 2^-1075) divided by the rise.
// Beyond 2^500 a product could overflow: no margin is finite there.
inline double crossing_margin(double largest_u, double largest_v, double smallest_rise) {
    if (!(largest_u <= 0x1p500 && largest_v <= 0x1p500 && smallest_rise > 0)) return HUGE_VAL;
    return 0x1p-46 * largest_u + DBL_MIN + 0x1p-1068 / smallest_rise;
}

// The outline's extent in v, and in u widened by its crossing margin. A point outside it
// is outside the polygon, as the count over every edge would say: below v_low or from
// v_high up, no edge straddles its v; right of u_high, no straddling edge's crossing lies
// beyond it; left of u_low, every straddling edge's does, and a closed outline has an even
// number of edges straddling any v. NaN is outside too, as the count says.
struct OutlineBox {
    double u_low = 0, u_high = 0, v_low = 0, v_high = 0;

    static OutlineBox of(std::span<const Point2> outline) {
        double u_min = outline[0].u, u_max = u_min, v_min = outline[0].v, v_max = v_min;
        double largest_u = 0, largest_v = 0, smallest_rise = HUGE_VAL;
        for (std::size_t i = 0, j = outline.size() - 1; i < outline.size(); j = i++) {
            const Point2& q = outline[i];
            u_min = std::fmin(u_min, q.u);
            u_max = std::fmax(u_max, q.u);
            v_min = std::fmin(v_min, q.v);
            v_max = std::fmax(v_max, q.v);
            largest_u = std::fmax(largest_u, std::fabs(q.u));
            largest_v = std::fmax(largest_v, std::fabs(q.v));
            const double rise = std::fabs(outline[j].v - q.v);
            if (rise > 0) smallest_rise = std::fmin(smallest_rise, rise);
        }
        const double margin = crossing_margin(largest_u, largest_v, smallest_rise);
        return {u_min - margin, u_max + margin, v_min, v_max};
    }

    // False only where the even-odd count is surely even.
    bool may_hold(Point2 p) const {
        return p.v >= v_low && p.v < v_high && p.u >= u_low && p.u <= u_high;
    }
};

}  // namespace rt::polygon
