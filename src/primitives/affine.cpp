// Affine (ID 7): O; X; Y; Z; then an inner primitive (ID and numbers, no surface). The inner
// primitive lives in the frame whose origin and axes appear in the world as O, X, Y, Z
// (section 2.7 of the original): a world ray is carried into that frame, intersected there,
// and the inner normal is carried back by the transpose of F^-1.
#include <cmath>

#include "affine_frame.h"
#include "primitives/primitives.h"
#include "rt/reader.h"

namespace rt::affine {

namespace {
struct Affine {
    AffineFrame frame;
    Shape inner;
    Bounds box;  // the world box of the inner primitive's box, computed once
};
}  // namespace

ShapeData read(SceneReader& reader) {
    const AffineFrame frame = read_affine_frame(reader, "affine");
    Shape inner = reader.shape("affine inner primitive");
    const Bounds box = frame.to_world_bounds(inner.bounds());
    return std::make_shared<const Affine>(Affine{frame, std::move(inner), box});
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    const auto& a = *static_cast<const Affine*>(shape);
    // The local ray M(o - O) + t' Md/|Md|, with t' = t |Md|: the interval scales the same way.
    const Vec3 local_direction = a.frame.to_local_direction(ray.direction);
    const double scale = length(local_direction);
    if (!(scale > 0) || !std::isfinite(scale)) return false;
    const Ray local{a.frame.to_local_point(ray.origin), local_direction / scale};
    Hit local_hit;
    if (!a.inner.intersect(local, {range.t_min * scale, range.t_max * scale}, local_hit))
        return false;
    const double t = local_hit.t / scale;
    // Dividing back can round just outside the range the inner primitive kept to.
    if (!range.contains(t)) return false;
    hit = {t, local_hit.part};
    return true;
}

Vec3 normal(const void* shape, const Vec3& point, const Hit& hit) {
    const auto& a = *static_cast<const Affine*>(shape);
    const Vec3 local_normal = a.inner.normal(a.frame.to_local_point(point), hit);
    return normalized(a.frame.normal_to_world(local_normal));
}

Bounds bounds(const void* shape) { return static_cast<const Affine*>(shape)->box; }

bool has_inside(const void* shape) { return static_cast<const Affine*>(shape)->inner.has_inside(); }

bool inside(const void* shape, const Vec3& point) {
    const auto& a = *static_cast<const Affine*>(shape);
    return a.inner.has_inside() && a.inner.inside(a.frame.to_local_point(point));
}

}  // namespace rt::affine
