// Image-mapped surface (ID 108): O; U; V; a PPM file path; then a base surface. The base
// surface's colour is replaced by the image's colour at u = (p - O).U / |U|^2,
// v = (p - O).V / |V|^2, each taken modulo 1, with v = 0 at the image's bottom row. The lookup
// takes the nearest pixel: the pixel whose square holds (u, v), no filtering.
#include <cmath>

#include "scene/texture.h"
#include "rt/reader.h"
#include "surfaces/surfaces.h"

namespace rt::image_surface {

namespace {
struct ImageSurface {
    Vec3 origin;
    Vec3 to_u;  // U / |U|^2, so that u = to_u . (p - O)
    Vec3 to_v;  // V / |V|^2
    std::shared_ptr<const Image> image;  // shared by every surface naming the same file
    SurfacePtr base;
};

// The pixel, of `count` along one side, that a texture coordinate falls in after wrapping.
int pixel_index(double coordinate, int count) {
    // A point at infinity or NaN has no meaningful place on the image; take the first pixel.
    if (!std::isfinite(coordinate)) return 0;
    // In [0, 1] here: the subtraction rounds to exactly 1 for tiny negative coordinates, and
    // the product can round up to count. Both mean the last pixel, so clamp.
    const double wrapped = coordinate - std::floor(coordinate);
    const int index = static_cast<int>(wrapped * count);
    return index < count ? index : count - 1;
}
}  // namespace

SurfaceData read(SceneReader& reader) {
    const Vec3 origin = reader.vec3("image-mapped surface origin O");
    const Vec3 u = reader.nonzero_vec3("image-mapped surface U vector");
    const Vec3 v = reader.nonzero_vec3("image-mapped surface V vector");
    auto image = reader.texture("texture file path");
    SurfacePtr base = reader.surface();
    return std::make_shared<const ImageSurface>(ImageSurface{
        origin, u / length_squared(u), v / length_squared(v), std::move(image), std::move(base)});
}

Material evaluate(const void* surface, const Vec3& point) {
    const auto& s = *static_cast<const ImageSurface*>(surface);
    Material m = s.base->at(point);
    const Vec3 offset = point - s.origin;
    const int column = pixel_index(dot(s.to_u, offset), s.image->width);
    // Image rows run from the top; v = 0 is the bottom row.
    const int row = s.image->height - 1 - pixel_index(dot(s.to_v, offset), s.image->height);
    m.colour = s.image->at(column, row);
    return m;
}

}  // namespace rt::image_surface
