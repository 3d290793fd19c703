// Warnings, before rendering, about renders whose cost is extreme for what the scene and
// options ask (not errors: such a render is valid, only slow).
#pragma once

#include <string>
#include <vector>

#include "rt/options.h"
#include "rt/scene.h"

namespace rt {

// Shadow rays for the first hits alone above which rt warns: at some tens of millions a second
// per thread, well over an hour on a few threads.
inline constexpr double kExtremeShadowRays = 1e11;
// With no weight cut-off, a depth above this lets glass double the rays at every level past
// 2^(depth + 1) per pixel.
inline constexpr int kExtremeDepthWithoutCutoff = 16;

// One line per problem ("this render may take very long: ..."), without the "rt: warning: ".
std::vector<std::string> cost_warnings(const Scene& scene, const RenderOptions& options);

}  // namespace rt
