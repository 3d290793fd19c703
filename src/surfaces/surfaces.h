// The functions each surface's source file provides, for the table in surfaces/table.cpp.
#pragma once

#include "rt/surface.h"

namespace rt {
class SceneReader;
// Reads the eight numbers of a simple surface; other surfaces use it for their parts.
Material read_material(SceneReader& reader);
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

namespace rt::affine_surface {
ReadSurfaceFn read;
EvaluateSurfaceFn evaluate;
}  // namespace rt::affine_surface
