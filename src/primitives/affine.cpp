// Affine (ID 7): O; X; Y; Z; then an inner primitive (ID and numbers, no surface). The inner
// primitive lives in the frame whose origin and axes appear in the world as O, X, Y, Z
// (section 2.7 of the original): a world ray is carried into that frame, intersected there,
// and the inner normal is carried back by the transpose of F^-1.
#include <cmath>
#include <optional>

#include "rt/primitive.h"
#include "rt/reader.h"
#include "scene/affine_frame.h"

namespace rt::affine {

namespace {

struct Affine {
    AffineFrame frame;
    Shape inner;
    Bounds box;  // the world box of the inner primitive's box, computed once
};

ShapeData read(SceneReader& reader) {
    const AffineFrame frame = read_affine_frame(reader, "affine");
    Shape inner = reader.shape("affine inner primitive");
    const Bounds box = frame.to_world_bounds(inner.bounds());
    return std::make_shared<const Affine>(Affine{frame, std::move(inner), box});
}

// A world ray carried into the inner primitive's frame: M(o - O) + t' Md/|Md|, where the
// local distance t' is t |Md|, so a range scales by the same factor.
struct LocalRay {
    Ray ray;
    double scale;
    Interval range(Interval world) const { return {world.t_min * scale, world.t_max * scale}; }
};

std::optional<LocalRay> to_local(const Affine& a, const Ray& ray) {
    const Vec3 local_direction = a.frame.to_local_direction(ray.direction);
    const double scale = length(local_direction);
    if (!(scale > 0) || !std::isfinite(scale)) return std::nullopt;
    return LocalRay{{a.frame.to_local_point(ray.origin), local_direction / scale}, scale};
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    const auto& a = *static_cast<const Affine*>(shape);
    const auto local = to_local(a, ray);
    Hit local_hit;
    if (!local || !a.inner.intersect(local->ray, local->range(range), local_hit)) return false;
    const double t = local_hit.t / local->scale;
    // Dividing back can round just outside the range the inner primitive kept to.
    if (!range.contains(t)) return false;
    hit = local_hit;  // the part, and for CSG which operand and surface
    hit.t = t;
    return true;
}

bool collect(const void* shape, const Ray& ray, double t_min, Crossings& out) {
    const auto& a = *static_cast<const Affine*>(shape);
    const auto local = to_local(a, ray);
    if (!local) return a.inner.inside(a.frame.to_local_point(ray.origin));
    const std::size_t first = out.size();
    bool started_inside = a.inner.collect(local->ray, t_min * local->scale, out);
    // Going in or out is a property of the path, which the frame carries over unchanged; the
    // distances scale back. One that rounds back to t_min or before is already behind.
    std::size_t kept = first;
    for (std::size_t i = first; i < out.size(); ++i) {
        Crossing crossing = out[i];
        crossing.hit.t /= local->scale;
        if (crossing.hit.t > t_min)
            out[kept++] = crossing;
        else
            started_inside = crossing.entering;
    }
    out.resize(kept);
    return started_inside;
}

bool intersect_any(const void* shape, const Ray& ray, Interval range, Hit&) {
    const auto& a = *static_cast<const Affine*>(shape);
    const auto local = to_local(a, ray);
    return local && a.inner.intersect_any(local->ray, local->range(range));
}

Vec3 normal(const void* shape, const Vec3& point, const Hit& hit) {
    const auto& a = *static_cast<const Affine*>(shape);
    const Vec3 local_normal = a.inner.normal(a.frame.to_local_point(point), hit);
    return normalized(a.frame.normal_to_world(local_normal));
}

// The inner primitive's shading normal (its normal where it has none of its own, so that this
// is then the normal above, bit for bit), carried back as the normal is. The world normal
// given is of no use to the inner primitive, which asks for its own.
Vec3 shading_normal(const void* shape, const Vec3& point, const Hit& hit, const Vec3&) {
    const auto& a = *static_cast<const Affine*>(shape);
    const Vec3 local_normal = a.inner.shading_normal(a.frame.to_local_point(point), hit);
    return normalized(a.frame.normal_to_world(local_normal));
}

Bounds bounds(const void* shape) { return static_cast<const Affine*>(shape)->box; }

Bounds solid_bounds(const void* shape) {
    const auto& a = *static_cast<const Affine*>(shape);
    return a.frame.to_world_bounds(a.inner.solid_bounds());
}

bool has_inside(const void* shape) { return static_cast<const Affine*>(shape)->inner.has_inside(); }

bool carries_surfaces(const void* shape) {
    return static_cast<const Affine*>(shape)->inner.carries_surfaces();
}

bool many_parts(const void* shape) { return static_cast<const Affine*>(shape)->inner.many_parts(); }

bool inside(const void* shape, const Vec3& point) {
    const auto& a = *static_cast<const Affine*>(shape);
    return a.inner.has_inside() && a.inner.inside(a.frame.to_local_point(point));
}

}  // namespace

// Solid, and carrying surfaces, exactly when its inner primitive is, so it says so per
// instance; it forwards everything else to the inner primitive too.
extern const PrimitiveFunctions functions{.read = read,
                                          .intersect = intersect,
                                          .normal = normal,
                                          .bounds = bounds,
                                          .inside = inside,
                                          .has_inside = has_inside,
                                          .intersect_any = intersect_any,
                                          .carries_surfaces = carries_surfaces,
                                          .collect = collect,
                                          .solid_bounds = solid_bounds,
                                          .shading_normal = shading_normal,
                                          .many_parts = many_parts};

}  // namespace rt::affine
