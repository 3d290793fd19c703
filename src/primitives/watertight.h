// The ray-triangle test shared by the triangle (5) and the mesh (14): the watertight test of
// Woop, Benthin and Wald ("Watertight ray/triangle intersection", JCGT 2(1), 2013), in
// double precision throughout.
//
// The ray is carried into a frame of its own: the axis along which it travels fastest
// becomes z, and the other two are sheared so that the ray runs along z through (0, 0). A
// triangle is hit where (0, 0) lies inside its projection onto the xy plane, which three edge
// functions decide: the edge function of an edge p q is the cross product p x q of its
// projected end points, twice the signed area of the triangle (0, p, q). It depends on the
// edge's two end points alone, so two triangles sharing an edge decide alike on which side of
// that edge the ray passes, and no ray slips between them, whatever the rounding.
//
// That holds only if both compute the very same number. The paper relies on p x q and q x p
// rounding to exact opposites, which fails where a compiler fuses a multiply and a subtract
// into one FMA (the standard allows it, and GCC does it by default on machines with FMA).
// So each triangle keeps its vertices sorted (see SortedTriangle) and computes every edge
// function from the lower end point to the higher: the shared edge of two triangles is then
// the same expression on the same numbers in both.
#pragma once

#include <array>
#include <cmath>
#include <cstring>
#include <type_traits>
#include <utility>

#include "rt/ray.h"

namespace rt {

// Lexicographic order of points: by x, then y, then z. Distinct points are always ordered.
constexpr bool lexicographically_less(const Vec3& a, const Vec3& b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.z < b.z;
}

// The positions (0, 1, 2) of a triangle's three vertices sorted lexicographically, and
// whether that order reverses the written winding (an odd permutation).
struct SortedTriangle {
    std::array<int, 3> order;
    bool flipped;

    static SortedTriangle sort(const Vec3& v0, const Vec3& v1, const Vec3& v2) {
        SortedTriangle s{{0, 1, 2}, false};
        const Vec3* v[3] = {&v0, &v1, &v2};
        auto swap_if_greater = [&](int i, int j) {
            auto& a = s.order[static_cast<std::size_t>(i)];
            auto& b = s.order[static_cast<std::size_t>(j)];
            if (lexicographically_less(*v[b], *v[a])) {
                std::swap(a, b);
                s.flipped = !s.flipped;
            }
        };
        swap_if_greater(0, 1);
        swap_if_greater(1, 2);
        swap_if_greater(0, 1);
        return s;
    }
};

// The unit normal (v1 - v0) x (v2 - v0) / |...| of a triangle, or the zero vector when it has
// none because its vertices lie on one line (or two coincide) in double precision. The edges
// are scaled to a largest component of 1 first, so that neither the cross product nor its
// length can overflow or underflow.
inline Vec3 face_normal(const Vec3& v0, const Vec3& v1, const Vec3& v2) {
    const Vec3 a = v1 - v0, b = v2 - v0;
    const double a_size = max_abs_component(a), b_size = max_abs_component(b);
    if (!(a_size > 0) || !(b_size > 0)) return {};
    const Vec3 n = cross(a / a_size, b / b_size);
    const double n_size = max_abs_component(n);
    if (!(n_size > 0)) return {};
    return normalized(n / n_size);
}

// A ray prepared for many triangle tests.
class TriangleRay {
  public:
    explicit TriangleRay(const Ray& ray) : origin_{ray.origin.x, ray.origin.y, ray.origin.z} {
        const Vec3 d = ray.direction;
        const Vec3 size{std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)};
        kz_ = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
        kx_ = (kz_ + 1) % 3;
        ky_ = (kx_ + 1) % 3;
        sx_ = d[kx_] / d[kz_];
        sy_ = d[ky_] / d[kz_];
        sz_ = 1 / d[kz_];
    }

    // The distance t along the ray to where it crosses the triangle with vertices a < b < c
    // (lexicographically), or nothing when it misses or runs in the triangle's plane. t is
    // not checked against any range. Both sides of the triangle are hit.
    bool crosses(const Vec3& a, const Vec3& b, const Vec3& c, double& t) const {
        const Point pa = project(a), pb = project(b), pc = project(c);
        // Each vertex's weight is the edge function of the opposite edge, taken round the
        // triangle a -> b -> c -> a; the edge c a is computed as a c, then negated.
        const double wa = edge(pb, pc);
        const double wb = -edge(pa, pc);
        const double wc = edge(pa, pb);
        // (0, 0) lies inside when no two weights have opposite signs (zero is either).
        if ((wa < 0 || wb < 0 || wc < 0) && (wa > 0 || wb > 0 || wc > 0)) return false;
        const double det = wa + wb + wc;  // twice the projected triangle's signed area
        if (det == 0) return false;       // seen edge on
        // The weighted depths, scaled back to distances along the ray.
        t = (wa * pa.z + wb * pb.z + wc * pc.z) * sz_ / det;
        return true;
    }

  private:
    struct Point {
        double x, y, z;  // z: the depth along the ray's dominant axis, not yet divided by it
    };
    Point project(const Vec3& v) const {
        // Components by an indexed load rather than through Vec3's operator[], whose
        // selects were a tenth of the SPD nurbtst's instructions: the same differences, so
        // the same hits (docs/performance.md, "Triangle vertices by an indexed load").
        static_assert(sizeof(Vec3) == 3 * sizeof(double) && std::is_trivially_copyable_v<Vec3>);
        double c[3];
        std::memcpy(c, &v, sizeof c);
        const double px = c[kx_] - origin_[kx_], py = c[ky_] - origin_[ky_],
                     pz = c[kz_] - origin_[kz_];
        return {px - sx_ * pz, py - sy_ * pz, pz};
    }
    static double edge(const Point& p, const Point& q) { return p.x * q.y - p.y * q.x; }

    double origin_[3];
    int kx_, ky_, kz_;
    double sx_, sy_, sz_;
};

}  // namespace rt
