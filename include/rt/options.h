// What the command line controls about a render.
#pragma once

namespace rt {

enum class RenderMode { trace, depth, colour, normal };

struct RenderOptions {
    int max_depth = 7;         // -d: secondary rays deeper than this are not traced
    double min_weight = 0.01;  // -w: nor are rays whose weight falls below this
    RenderMode mode = RenderMode::trace;
    int samples = 1;  // -s: samples per pixel along each axis (supersampling)
    int threads = 0;  // -j: worker threads; 0 means one per hardware thread
    // --no-bvh turns this off: every ray is tested against every object in file order. The
    // image is the same either way; the linear scan is the oracle the hierarchy is tested by.
    bool accelerate = true;

    // Parts of the illumination model that the --no-* switches turn off, for testing.
    bool ambient = true;
    bool diffuse = true;
    bool specular = true;
    bool shadows = true;
    bool reflection = true;
    bool refraction = true;
};

}  // namespace rt
