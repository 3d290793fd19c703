// Affine surface (ID 111): O; X; Y; Z; then a surface, evaluated at the world point taken into
// the local frame (section 2.7 of the original: "similar primitives are provided for the
// affine distortion of surfaces"). A checker in a stretched frame gives stretched cells.
#include "scene/affine_frame.h"
#include "rt/reader.h"
#include "surfaces/surfaces.h"

namespace rt::affine_surface {

namespace {
struct AffineSurface {
    AffineFrame frame;
    SurfacePtr inner;
};
}  // namespace

SurfaceData read(SceneReader& reader) {
    const AffineFrame frame = read_affine_frame(reader, "affine surface");
    SurfacePtr inner = reader.surface();
    return std::make_shared<const AffineSurface>(AffineSurface{frame, std::move(inner)});
}

Material evaluate(const void* surface, const Vec3& point) {
    const auto& a = *static_cast<const AffineSurface*>(surface);
    return a.inner->at(a.frame.to_local_point(point));
}

}  // namespace rt::affine_surface
