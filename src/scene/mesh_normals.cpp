// Vertex normals for a mesh file that gives none (mode 2 of ID 15).
#include <cmath>

#include "scene/mesh_file.h"

namespace rt {

namespace {

// The angle between two non-zero vectors; atan2 keeps it accurate near 0 and pi, where acos
// of a dot product loses digits.
double angle_between(const Vec3& a, const Vec3& b) {
    return std::atan2(length(cross(a, b)), dot(a, b));
}

}  // namespace

std::vector<Vec3> angle_weighted_normals(std::span<const Vec3> positions,
                                         std::span<const std::array<std::uint32_t, 3>> triangles) {
    std::vector<Vec3> sums(positions.size());
    for (const auto& t : triangles) {
        const Vec3& a = positions[t[0]];
        const Vec3& b = positions[t[1]];
        const Vec3& c = positions[t[2]];
        const Vec3 n = cross(b - a, c - a);
        const double area2 = length(n);
        // A zero-area triangle has no normal and no angles to weight one with.
        if (!(area2 > 0) || !std::isfinite(area2)) continue;
        const Vec3 unit = n / area2;
        sums[t[0]] += unit * angle_between(b - a, c - a);
        sums[t[1]] += unit * angle_between(c - b, a - b);
        sums[t[2]] += unit * angle_between(a - c, b - c);
    }
    for (Vec3& s : sums) {
        const double l = length(s);
        s = l > 0 && std::isfinite(l) ? s / l : Vec3{};
    }
    return sums;
}

}  // namespace rt
