// Box (ID 12): min corner; max corner. The solid axis-aligned box between them, found by
// intersecting the ray with the three slabs min_k <= x_k <= max_k.
#include <array>
#include <string>

#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::box {

namespace {

struct Box {
    Vec3 min, max;
};

// Hit.part names the face, so the normal is exact even where faces meet: 2k is the face
// x_k = min_k and 2k + 1 the face x_k = max_k.
constexpr int face(int axis, bool at_max) { return 2 * axis + (at_max ? 1 : 0); }

ShapeData read(SceneReader& reader) {
    const Vec3 min = reader.vec3("box min corner");
    const Location max_at = reader.next_location();
    const Vec3 max = reader.vec3("box max corner");
    static constexpr std::array<const char*, 3> kAxisNames{"x", "y", "z"};
    for (int k = 0; k < 3; ++k)
        if (!(min[k] < max[k]))
            reader.fail(max_at, std::string("box max corner must exceed the min corner in every "
                                            "component, got ") +
                                    kAxisNames[static_cast<std::size_t>(k)] + " max " +
                                    format_number(max[k]) + " <= min " + format_number(min[k]));
    return reader.shape_data(Box{min, max});
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    const auto& b = *static_cast<const Box*>(shape);
    // The ray is in the box between t_enter and t_exit, entering and leaving by the faces
    // recorded with them.
    double t_enter = -kInfinity, t_exit = kInfinity;
    int enter_face = 0, exit_face = 0;
    for (int k = 0; k < 3; ++k) {
        const double o = ray.origin[k], d = ray.direction[k];
        if (d == 0) {
            // Parallel to this slab: inside it for every t or for none. Dividing would give
            // 0/0 = NaN for a ray that runs exactly along a face.
            if (o < b.min[k] || o > b.max[k]) return false;
            continue;
        }
        const bool forward = d > 0;
        const double t_near = ((forward ? b.min[k] : b.max[k]) - o) / d;
        const double t_far = ((forward ? b.max[k] : b.min[k]) - o) / d;
        if (t_near > t_enter) {
            t_enter = t_near;
            enter_face = face(k, !forward);
        }
        if (t_far < t_exit) {
            t_exit = t_far;
            exit_face = face(k, forward);
        }
    }
    if (t_enter > t_exit) return false;
    // A ray that starts inside (or whose entry is before t_min) meets the far face.
    if (range.contains(t_enter)) {
        hit = {t_enter, enter_face};
        return true;
    }
    if (range.contains(t_exit)) {
        hit = {t_exit, exit_face};
        return true;
    }
    return false;
}

Vec3 normal(const void*, const Vec3&, const Hit& hit) {
    const int axis = hit.part / 2;
    const double sign = hit.part % 2 == 1 ? 1 : -1;
    return {axis == 0 ? sign : 0, axis == 1 ? sign : 0, axis == 2 ? sign : 0};
}

Bounds bounds(const void* shape) {
    const auto& b = *static_cast<const Box*>(shape);
    return {b.min, b.max};
}

bool inside(const void* shape, const Vec3& point) {
    const auto& b = *static_cast<const Box*>(shape);
    return point.x > b.min.x && point.x < b.max.x && point.y > b.min.y && point.y < b.max.y &&
           point.z > b.min.z && point.z < b.max.z;
}

}  // namespace

extern const PrimitiveFunctions functions{
    .read = read, .intersect = intersect, .normal = normal, .bounds = bounds, .inside = inside};

}  // namespace rt::box
