// One fuzz case, shared by the libFuzzer target (fuzz_reader.cpp) and the deterministic fuzz
// test in ctest (test_fuzz.cpp): read the bytes as a scene and, if they read, render a few
// pixels. A scene error must be an rt::Error whose message starts with its place; anything
// else (another exception, a crash, a sanitizer report) is a finding.
#pragma once

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <string_view>

#include "rt/error.h"
#include "rt/reader.h"
#include "rt/render.h"

namespace rt_fuzz {

// Whether `message` starts "name:line:col: ": the input's name or one a line marker gave (any
// non-empty name), line and column whole numbers >= 1.
inline bool has_place(std::string_view message) {
    const std::string_view line = message.substr(0, message.find('\n'));
    for (std::size_t colon = line.find(':', 1); colon != std::string_view::npos;
         colon = line.find(':', colon + 1)) {
        std::size_t i = colon;
        bool numbers = true;
        for (int field = 0; field < 2 && numbers; ++field) {
            const std::size_t start = ++i;
            while (i < line.size() && line[i] >= '0' && line[i] <= '9') ++i;
            numbers = i > start && line[start] != '0' && i < line.size() && line[i] == ':';
        }
        if (numbers && line.substr(i, 2) == ": ") return true;
    }
    return false;
}

struct Outcome {
    bool read = false;   // the scene was read (and rendered)
    std::string error;   // the rt::Error's message otherwise
    bool placed = true;  // the error names its place
};

// The render's size: 3 x 3 pixels, depth 4.
inline constexpr int kPixels = 3;
inline constexpr int kDepth = 4;

// Whether rendering the scene stays within the few milliseconds a case may take. Shadow rays
// are bounded by the lights' samples. Triangles are bounded too: a mesh placed by a few bytes
// holds thousands, and where no box can tell them apart (a ray from 1e26 away, whose origin's
// rounding is larger than the mesh) a ray tests every one. That is the cost of the linear scan
// and no hang, but at most kPixels^2 x (rays of a pixel's tree) x (1 + samples) x triangles
// tests under the sanitizers can take minutes, so such scenes are only read.
inline bool cheap_to_render(const rt::Scene& scene) {
    long samples = 0;
    for (const rt::Light& light : scene.lights) samples += light.sample_count();
    if (samples > 4096) return false;
    // A pixel's ray tree: a chain of kDepth + 1 rays, or a full binary tree where surfaces both
    // reflect and refract.
    const double rays = kPixels * kPixels * (scene.splits_rays ? (2 << kDepth) - 1 : kDepth + 1) *
                        (1.0 + static_cast<double>(samples));
    return rays * static_cast<double>(scene.mesh_triangles) <= 1e6;
}

// Textures are looked for in `base_dir`. Renders only scenes that are cheap to render, at
// kPixels x kPixels, so that every case takes milliseconds.
inline Outcome fuzz_one(std::string_view bytes, const std::filesystem::path& base_dir) {
    constexpr std::string_view kName = "fuzz.in";
    Outcome outcome;
    std::istringstream in{std::string(bytes)};
    try {
        rt::Scene scene = rt::read_scene(in, std::string(kName), base_dir, 1);
        if (cheap_to_render(scene)) {
            scene.viewer.xres = std::min(scene.viewer.xres, kPixels);
            scene.viewer.yres = std::min(scene.viewer.yres, kPixels);
            rt::RenderOptions options;
            options.threads = 1;
            options.max_depth = kDepth;
            rt::render(scene, options);
        }
        outcome.read = true;
    } catch (const rt::Error& e) {
        outcome.error = e.what();
        outcome.placed = has_place(outcome.error);
    }
    return outcome;
}

}  // namespace rt_fuzz
