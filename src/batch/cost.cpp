#include "batch/cost.h"

#include <cstdio>

namespace rt {

std::vector<std::string> cost_warnings(const Scene& scene, const RenderOptions& options) {
    std::vector<std::string> warnings;
    if (options.mode != RenderMode::trace) return warnings;
    if (options.shadows && options.diffuse) {
        double light_samples = 0;
        for (const Light& light : scene.lights) light_samples += light.sample_count();
        const double pixels = static_cast<double>(scene.viewer.xres) * scene.viewer.yres;
        // Adaptive supersampling gives most pixels one ray: count those only.
        const double rays = options.adaptive_threshold
                                ? 1.0
                                : static_cast<double>(options.samples) * options.samples;
        const double shadow_rays = pixels * rays * light_samples;
        if (shadow_rays > kExtremeShadowRays) {
            char text[256];
            std::snprintf(text, sizeof text,
                          "this render may take very long: %dx%d pixels x %.0f rays x %.0f light "
                          "samples is %.3g shadow rays for the first hits alone (fewer sphere "
                          "light samples or a smaller --size make it faster)",
                          scene.viewer.xres, scene.viewer.yres, rays, light_samples, shadow_rays);
            warnings.emplace_back(text);
        }
    }
    if (options.min_weight == 0 && options.max_depth > kExtremeDepthWithoutCutoff &&
        options.reflection && options.refraction && scene.splits_rays)
        warnings.push_back("-d " + std::to_string(options.max_depth) +
                           " with -w 0: each glass surface can double the rays at every level, up "
                           "to 2^" +
                           std::to_string(options.max_depth + 1) +
                           " per pixel; a weight cut-off (-w 0.001) bounds it");
    return warnings;
}

}  // namespace rt
