// A scene as the reader returns it: a value with no ties to global state.
#pragma once

#include <vector>

#include "rt/light.h"
#include "rt/primitive.h"
#include "rt/surface.h"
#include "rt/viewer.h"

namespace rt {

// A primitive placed in the scene with its surface.
struct Object {
    Shape shape;
    SurfacePtr surface;
};

struct Scene {
    Viewer viewer;
    std::vector<Object> objects;
    std::vector<Light> lights;
    Spectrum ambient{0.0};  // the sum of the ambient lights (ID 103)
};

}  // namespace rt
