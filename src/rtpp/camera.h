// The camera as people describe one, turned into the viewer's numbers (102): the image
// plane's half-width and half-height vectors at one unit from the eye.
#pragma once

#include "rt/vec.h"

namespace rtpp {

using rt::Vec3;

struct Camera {
    Vec3 position;
    Vec3 look_at;
    Vec3 up{0, 1, 0};
    double half_width = 0;  // tan(horizontal field of view / 2)
    int width = 0;
    int height = 0;
    // Upright keeps vertical lines vertical (a view camera's rising front): y is the up
    // vector itself rather than the view's own up, so the image plane is not square to the
    // line of sight when looking up or down.
    bool upright = false;
};

struct ViewerVectors {
    Vec3 x;  // to the right, half the image's width
    Vec3 y;  // upward, half its height: |y| / |x| = height / width, so pixels are square
};

// Throws std::invalid_argument, with a message, when the camera has no
// direction (position = look_at) or looks along its up vector.
ViewerVectors viewer_vectors(const Camera& camera);

}  // namespace rtpp
