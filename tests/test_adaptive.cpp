// Adaptive supersampling (-a): which pixels get the N x N grid, that they get exactly the -s N
// value, that the rest keep the one-ray value, and the rays it costs.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "rt/render.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

// A lit sphere in front of a plane, with black sky above the plane's horizon: edges, smooth
// gradients, highlights brighter than 1 and flat regions.
const std::string kScene =
    "102  0 1 6  0 0 0  0.6 0 0  0 0.4 0  37 23\n"
    "1 1  0 0 0  100 1 0.5 0.25 0.3 20 0.8 0 1\n"
    "2 -1  0 1 0  100 0.2 0.6 0.3 0 1 0.9 0 1\n"
    "101 2 4 4  60 60 60\n";

Raster render_with(const Scene& scene, int samples, std::optional<double> threshold,
                   int threads = 2, RenderStats* stats = nullptr) {
    RenderOptions options;
    options.samples = samples;
    options.adaptive_threshold = threshold;
    options.threads = threads;
    return render(scene, options, stats);
}

bool same_image(const Raster& a, const Raster& b) {
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            if (!(a.at(x, y) == b.at(x, y))) return false;
    return a.width() == b.width() && a.height() == b.height();
}

// The pixels that the documented rule supersamples, worked out here from the one-ray image:
// some 4-connected neighbour differs by more than the threshold in a clamped component.
std::vector<bool> expected_supersampled(const Raster& one_ray, double threshold) {
    const int w = one_ray.width(), h = one_ray.height();
    const auto differs = [&](int x, int y, int nx, int ny) {
        if (nx < 0 || ny < 0 || nx >= w || ny >= h) return false;
        for (std::size_t i = 0; i < kSpectrumComponents; ++i) {
            const double a = std::clamp(one_ray.at(x, y)[i], 0.0, 1.0);
            const double b = std::clamp(one_ray.at(nx, ny)[i], 0.0, 1.0);
            if (std::fabs(a - b) > threshold) return true;
        }
        return false;
    };
    std::vector<bool> flags;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            flags.push_back(differs(x, y, x - 1, y) || differs(x, y, x + 1, y) ||
                            differs(x, y, x, y - 1) || differs(x, y, x, y + 1));
    return flags;
}

std::uint64_t pixel_count(const Scene& scene) {
    return static_cast<std::uint64_t>(scene.viewer.xres) * scene.viewer.yres;
}

}  // namespace

TEST(a_threshold_above_every_difference_gives_the_one_ray_image) {
    const Scene scene = parse_scene(kScene);
    const Raster one_ray = render_with(scene, 1, std::nullopt);
    for (double threshold : {1.0, 5.0}) {
        RenderStats stats;
        CHECK(same_image(render_with(scene, 3, threshold, 2, &stats), one_ray));
        CHECK_EQ(stats.primary_rays, pixel_count(scene));
    }
}

TEST(exactly_the_pixels_with_a_differing_neighbour_get_the_grid) {
    const Scene scene = parse_scene(kScene);
    const Raster one_ray = render_with(scene, 1, std::nullopt);
    for (int n : {2, 3, 4}) {
        const Raster grid = render_with(scene, n, std::nullopt);
        for (double threshold : {0.0, 0.02, 0.2}) {
            RenderStats stats;
            const Raster adaptive = render_with(scene, n, threshold, 2, &stats);
            const std::vector<bool> flags = expected_supersampled(one_ray, threshold);
            std::uint64_t supersampled = 0;
            bool as_expected = true;
            for (int y = 0; y < scene.viewer.yres; ++y)
                for (int x = 0; x < scene.viewer.xres; ++x) {
                    const bool flagged = flags[static_cast<std::size_t>(y) * scene.viewer.xres + x];
                    supersampled += flagged ? 1 : 0;
                    as_expected =
                        as_expected && adaptive.at(x, y) == (flagged ? grid : one_ray).at(x, y);
                }
            CHECK(as_expected);
            // The scene has both kinds of pixel at every threshold tried.
            CHECK(supersampled > 0 && supersampled < pixel_count(scene));
            // An odd grid reuses the one ray it shares with the one-ray image.
            const std::uint64_t extra = static_cast<std::uint64_t>(n * n) - (n % 2 == 1 ? 1 : 0);
            CHECK_EQ(stats.primary_rays, pixel_count(scene) + supersampled * extra);
        }
    }
}

TEST(adaptive_images_are_the_same_on_any_number_of_threads) {
    const Scene scene = parse_scene(kScene);
    const Raster one_thread = render_with(scene, 3, 0.05, 1);
    for (int threads : {2, 3, 8})
        CHECK(same_image(render_with(scene, 3, 0.05, threads), one_thread));
}

TEST(a_flat_image_traces_one_primary_ray_per_pixel) {
    for (const char* sky : {"", "103 0.3 0.2 0.1\n"}) {
        const Scene scene = parse_scene(std::string(kTestViewer) + sky);
        RenderStats stats;
        const Raster image = render_with(scene, 3, 0.0, 2, &stats);
        CHECK_EQ(stats.primary_rays, pixel_count(scene));
        CHECK(same_image(image, render_with(scene, 1, std::nullopt)));
    }
}

TEST(values_are_compared_clamped_as_they_are_written) {
    // Sky 2 and a sphere of 1.6 (ambient 2 x kd 0.8): different values, the same white when
    // written, so nothing is supersampled even at threshold 0.
    std::string text = kTestViewer;
    text += "103 2 2 2\n1 1  0 0 0  100 1 1 1 0 1 0.8 0 1\n";
    const Scene scene = parse_scene(text);
    RenderStats stats;
    render_with(scene, 3, 0.0, 2, &stats);
    CHECK_EQ(stats.primary_rays, pixel_count(scene));
}
