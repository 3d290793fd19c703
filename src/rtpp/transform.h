// Affine frames as the numeric format writes them (origin O and axes X, Y, Z: a local point
// p is the world point O + p.x X + p.y Y + p.z Z), and the transforms that build them.
// Transforms apply in the order written, each to the result of those before it.
#pragma once

#include "rt/vec.h"

namespace rtpp {

using rt::Vec3;

struct Frame {
    Vec3 origin{0, 0, 0};
    Vec3 x{1, 0, 0};
    Vec3 y{0, 1, 0};
    Vec3 z{0, 0, 1};

    bool is_identity() const { return *this == Frame{}; }
    bool operator==(const Frame&) const = default;
    Vec3 point(const Vec3& p) const { return origin + (x * p.x + y * p.y + z * p.z); }
    Vec3 direction(const Vec3& d) const { return x * d.x + y * d.y + z * d.z; }
};

// `outer` applied after `inner`: the frame of a thing placed by inner, then by outer.
Frame compose(const Frame& outer, const Frame& inner);

Frame translation(const Vec3& offset);
Frame scaling(const Vec3& factors);
// A rotation by `degrees` about `axis` (through the origin, right-handed). Multiples of 90
// degrees are exact, so a quarter turn writes 0 and 1, not 6e-17.
Frame rotation(double degrees, const Vec3& axis);

// Sine and cosine of an angle in degrees, exact at multiples of 90 (and of 30 for the sine
// and 60 for the cosine, where the value is 0.5).
double sin_degrees(double degrees);
double cos_degrees(double degrees);
// Exact at multiples of 45 degrees too; infinite at odd multiples of 90.
double tan_degrees(double degrees);

// v divided by its length, component by component: a vector along an axis comes out as
// exactly 1 along it (v * (1 / |v|) need not).
Vec3 unit(const Vec3& v);

}  // namespace rtpp
