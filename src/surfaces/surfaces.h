// The functions each surface's source file provides, for the table in surfaces/table.cpp.
#pragma once

#include <string_view>

#include "rt/surface.h"

namespace rt {
class SceneReader;
// Reads the eight numbers of a simple surface; other surfaces use it for their parts.
Material read_material(SceneReader& reader);
// Reads the four fields that the simple and glass surfaces begin with: colour, ks, ke, kd.
Material read_shading(SceneReader& reader);
// Reads three numbers, each >= 0 ("<what> components must be >= 0" at the first otherwise).
Spectrum read_non_negative_spectrum(SceneReader& reader, std::string_view what);
}  // namespace rt

namespace rt::simple_surface {
ReadSurfaceFn read;
EvaluateSurfaceFn evaluate;
}  // namespace rt::simple_surface

namespace rt::checker_surface {
ReadSurfaceFn read;
EvaluateSurfaceFn evaluate;
}  // namespace rt::checker_surface

namespace rt::image_surface {
ReadSurfaceFn read;
EvaluateSurfaceFn evaluate;
}  // namespace rt::image_surface

namespace rt::glass_surface {
ReadSurfaceFn read;  // evaluated by simple_surface::evaluate: it holds a Material too
}  // namespace rt::glass_surface

namespace rt::affine_surface {
ReadSurfaceFn read;
EvaluateSurfaceFn evaluate;
}  // namespace rt::affine_surface
