// What the command line controls about a render.
#pragma once

#include <optional>

namespace rt {

// The grid size -a uses when -s is not given: 3 x 3, as POV-Ray's +A users expect.
inline constexpr int kDefaultAdaptiveSamples = 3;

enum class RenderMode { trace, depth, colour, normal };

class RayQueries;  // rt/trace.h

struct RenderOptions {
    int max_depth = 7;         // -d: secondary rays deeper than this are not traced
    double min_weight = 0.01;  // -w: nor are rays whose weight falls below this
    RenderMode mode = RenderMode::trace;
    int samples = 1;  // -s: samples per pixel along each axis (supersampling)
    // -a: when set, pixels get one ray each, and only those that differ from a neighbour by
    // more than this (clamped, in any component) get the samples x samples grid.
    std::optional<double> adaptive_threshold;
    int threads = 0;  // -j: worker threads; 0 means one per hardware thread
    // --no-bvh turns this off: every ray is tested against every object in file order. The
    // image is the same either way; the linear scan is the oracle the hierarchy is tested by.
    bool accelerate = true;
    // Not a command-line option: when set, this answers every ray query instead of the
    // hierarchy or the linear scan (a hook for measuring another library's ray queries under
    // rt's shading, bench/embree), whatever `accelerate` says. It must outlive the render.
    const RayQueries* queries = nullptr;

    // Parts of the illumination model that the --no-* switches turn off, for testing.
    bool ambient = true;
    bool diffuse = true;
    bool specular = true;
    bool shadows = true;
    bool reflection = true;
    bool refraction = true;
};

}  // namespace rt
