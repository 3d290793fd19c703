#include "rtpp/camera.h"

#include <cmath>
#include <stdexcept>

#include "rtpp/transform.h"

namespace rtpp {

ViewerVectors viewer_vectors(const Camera& camera) {
    const Vec3 view = camera.look_at - camera.position;
    if (!(rt::length(view) > 0))
        throw std::invalid_argument("camera look_at must differ from its position");
    const Vec3 right_dir = rt::cross(view, camera.up);
    if (!(rt::length(right_dir) > 0) || !std::isfinite(rt::length(right_dir)))
        throw std::invalid_argument("camera up must not be zero or along the line of sight");
    const Vec3 right = unit(right_dir);
    const Vec3 up = camera.upright ? unit(camera.up) : unit(rt::cross(right, view));
    const double half_height = camera.half_width * camera.height / camera.width;
    return {right * camera.half_width, up * half_height};
}

}  // namespace rtpp
