// The frame shared by the affine primitive (7), surface (111) and light (112): a local point p
// is the world point O + p.x X + p.y Y + p.z Z (section 2.7 of the original). With F = [X Y Z]
// (columns) and M = F^-1, a world point x is the local point M (x - O).
#pragma once

#include <string>
#include <string_view>

#include "rt/ray.h"

namespace rt {

class SceneReader;

// A frame is refused when |det F| <= kSingularFrameTolerance |X| |Y| |Z|. By Hadamard's
// inequality |det F| <= |X| |Y| |Z|, with equality for perpendicular axes, so the ratio is
// scale-free: it measures how flat the frame is (about the sine of the smallest angle between
// an axis and the plane of the other two), not how large. A uniformly tiny frame is fine;
// one whose axes are dependent to within rounding is not, since M would be mostly noise.
inline constexpr double kSingularFrameTolerance = 1e-12;

struct AffineFrame {
    Vec3 origin;            // O
    Vec3 x, y, z;           // the columns of F: the local axes as they appear in the world
    Vec3 row0, row1, row2;  // the rows of M = F^-1

    // Local from world.
    Vec3 to_local_direction(const Vec3& d) const {
        return {dot(row0, d), dot(row1, d), dot(row2, d)};
    }
    Vec3 to_local_point(const Vec3& p) const { return to_local_direction(p - origin); }
    // World from local.
    Vec3 to_world_direction(const Vec3& d) const { return d.x * x + d.y * y + d.z * z; }
    Vec3 to_world_point(const Vec3& p) const { return origin + to_world_direction(p); }
    // M^T n: a gradient (a normal) in the local frame carried to the world by the chain rule,
    // grad_x f(M x) = M^T grad_y f(y). Not normalised.
    Vec3 normal_to_world(const Vec3& n) const { return n.x * row0 + n.y * row1 + n.z * row2; }

    // The axis-aligned box holding the image of a local box: per world axis, the sum of the
    // intervals F_ij [min_j, max_j], which is exactly the box of the 8 transformed corners.
    // Infinite local extents stay infinite, and a zero entry of F never multiplies one.
    Bounds to_world_bounds(const Bounds& local) const;
};

// Why the axes X, Y, Z make no usable frame ("is singular: ..."), or "" when they do.
std::string frame_problem(const Vec3& x, const Vec3& y, const Vec3& z);

// Builds the frame; the axes must have passed frame_problem.
AffineFrame make_affine_frame(const Vec3& origin, const Vec3& x, const Vec3& y, const Vec3& z);

// Reads O, X, Y, Z (12 numbers) for the object named `what` ("affine", "affine surface", ...)
// and reports a singular frame at the X field.
AffineFrame read_affine_frame(SceneReader& reader, std::string_view what);

}  // namespace rt
