// Cone (ID 8): alpha = cos(half-angle); start; finish; apex c; axis a. The double cone
// ((x - c).a_hat)^2 = alpha^2 |x - c|^2 (section 2.8 of the original), kept where
// start <= (x - c).a / |a|^2 <= finish. It is open: there are no caps.
#include <cmath>

#include "primitives/axial.h"
#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::cone {

namespace {

struct Cone {
    AxialExtent extent;
    double cos2;               // alpha^2, the original's one precomputed value
    double sin2;               // 1 - alpha^2
    double radius_per_height;  // tan(half-angle), for the bounds
};

ShapeData read(SceneReader& reader) {
    const Location alpha_at = reader.next_location();
    const double alpha = reader.number("cone alpha (cos of the half-angle)");
    if (!(alpha > 0 && alpha < 1))
        reader.fail(alpha_at, "cone alpha (cos of the half-angle) must be > 0 and < 1, got " +
                                  format_number(alpha));
    const AxialExtent extent = read_axial_extent(reader, "cone", "apex");
    // 1 - alpha^2 as a product, exact enough even when alpha is close to 1.
    const double sin2 = (1 - alpha) * (1 + alpha);
    return reader.shape_data(Cone{extent, alpha * alpha, sin2, std::sqrt(sin2) / alpha});
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    const auto& k = *static_cast<const Cone*>(shape);
    const Vec3& axis = k.extent.axis;
    // The offset from the apex and the direction, split along and across the axis.
    const AxialRay r(k.extent, ray);
    const auto& [w, w_along, d_along, w_across, d_across] = r;
    // The quadratic A t^2 + 2 B t + C = 0 of the original, written with cos^2 and sin^2 so
    // that no term is 1 - (d.a)^2 (which cancels for rays near the axis).
    const double a = k.cos2 * length_squared(d_across) - k.sin2 * d_along * d_along;
    const double b = k.cos2 * dot(w_across, d_across) - k.sin2 * w_along * d_along;
    const double c = k.cos2 * length_squared(w_across) - k.sin2 * w_along * w_along;
    // B^2 - A C expands to cos^2 (sin^2 |m|^2 - cos^2 s^2), with m = w_along d_across -
    // d_along w_across and s = (w x d).axis: a difference of two meaningful squares instead
    // of two nearly equal products.
    const Vec3 m = w_along * d_across - d_along * w_across;
    const double s = dot(cross(w, ray.direction), axis);
    const double discriminant = k.cos2 * (k.sin2 * length_squared(m) - k.cos2 * s * s);
    if (!(discriminant >= 0)) return false;
    return nearest_kept_root(solve_quadratic(a, b, c, discriminant), range, k.extent, r, hit);
}

Vec3 normal(const void* shape, const Vec3& point, const Hit&) {
    const auto& k = *static_cast<const Cone*>(shape);
    const Vec3& axis = k.extent.axis;
    // Minus the gradient of ((x - c).a)^2 - alpha^2 |x - c|^2, which points away from the
    // axis on both nappes. Scaling v first keeps points very near the apex from underflowing.
    const Vec3 v = point - k.extent.origin;
    const double scale = max_abs_component(v);
    // At the apex itself the surface has no normal; the axis is as good as any.
    if (!(scale > 0)) return axis;
    const Vec3 unit_v = v / scale;
    return normalized(k.cos2 * unit_v - dot(unit_v, axis) * axis);
}

Bounds bounds(const void* shape) {
    const auto& k = *static_cast<const Cone*>(shape);
    return axial_bounds(k.extent, std::fabs(k.extent.near) * k.radius_per_height,
                        std::fabs(k.extent.far) * k.radius_per_height);
}

}  // namespace

extern const PrimitiveFunctions functions{
    .read = read, .intersect = intersect, .normal = normal, .bounds = bounds};

}  // namespace rt::cone
