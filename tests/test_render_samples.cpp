// A render kept as samples (render_region_samples, what rt does for a PPM or PNG): the bytes
// of the raster's samples for every scene, with supersampling and adaptive supersampling,
// 8 and 16 bits, every gamma, any region and any number of threads; and through the real
// binary, the file the raster of the same render encodes to.
#include <algorithm>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "check.h"
#include "cli_util.h"
#include "rt/image_io.h"
#include "rt/reader.h"
#include "rt/render.h"
#include "scene_util.h"

namespace fs = std::filesystem;
using namespace rt;
using namespace rt_test;

namespace {

const Gamma kGammas[] = {{}, {Gamma::Kind::srgb, 1}, {Gamma::Kind::power, 2.2}};

bool same_samples(const SampleRaster& samples, const SampleImage& expected) {
    return samples.width() == expected.width && samples.height() == expected.height &&
           std::equal(samples.bytes().begin(), samples.bytes().end(), expected.bytes.begin(),
                      expected.bytes.end());
}

// Every way of rendering a scene a test here tries: one ray, a grid, adaptive.
std::vector<RenderOptions> option_sets() {
    RenderOptions grid;
    grid.samples = 2;
    RenderOptions adaptive;
    adaptive.samples = 3;
    adaptive.adaptive_threshold = 0.02;
    return {RenderOptions{}, grid, adaptive};
}

}  // namespace

TEST(samples_of_every_scene_are_the_rasters_quantized) {
    std::mt19937 random(20261205);
    int compared = 0;
    for (const fs::path& file : files_with_extension(fs::path(RT_SOURCE_DIR) / "scenes", ".in")) {
        Scene scene = read_scene_file(file.string());
        // At most 40 pixels a side, so that every scene is quick.
        const double shrink = std::min(1.0, 40.0 / std::max(scene.viewer.xres, scene.viewer.yres));
        scene.viewer.xres = std::max(1, static_cast<int>(scene.viewer.xres * shrink));
        scene.viewer.yres = std::max(1, static_cast<int>(scene.viewer.yres * shrink));
        const int w = scene.viewer.xres, h = scene.viewer.yres;
        for (RenderOptions options : option_sets()) {
            const auto pick = [&](int n) {
                return std::uniform_int_distribution<int>(0, n - 1)(random);
            };
            const int x0 = pick(w), y0 = pick(h);
            for (const PixelRect region :
                 {image_rect(scene.viewer),
                  PixelRect{x0, y0, x0 + 1 + pick(w - x0), y0 + 1 + pick(h - y0)}}) {
                options.threads = 2;
                RenderStats expected_stats;
                const Raster raster = render_region(scene, options, region, &expected_stats);
                for (const int bits : {8, 16})
                    for (const Gamma& gamma : kGammas) {
                        options.threads = 1 + pick(4);
                        RenderStats stats;
                        const SampleRaster samples =
                            render_region_samples(scene, options, region, bits, gamma, &stats);
                        if (!same_samples(samples, quantize(raster, bits, gamma)))
                            record_failure(
                                __FILE__, __LINE__,
                                join(file.filename().string(), ": samples of region ", region.x0,
                                     ",", region.x1, ",", region.y0, ",", region.y1, " at ", bits,
                                     " bits on ", options.threads,
                                     " threads differ from the raster's"));
                        CHECK_EQ(stats.total(), expected_stats.total());
                        ++compared;
                    }
            }
        }
    }
    CHECK(compared >= 30 * 3 * 2 * 6);
}

// Over-exposed highlights (values above 1), black and everything between, through the binary:
// a PPM or PNG from the samples is the file the raster of the same render encodes to.
TEST(rt_writes_the_file_the_rasters_encoding_gives) {
    const std::string text =
        "102 0 0 5 0 0 0 1 0 0 0 .75 0 23 17\n"
        "101 -3 4 5 80 60 50\n103 .05 .08 .1\n"
        "1 0.9 0.2 0 0 100 .9 .6 .3 .6 20 .8 0 1\n"
        "1 0.5 -1 -0.6 0.5 114 1 1 1 0.1 50 0 1.5 0 0 0\n";
    const fs::path dir = work_dir("render_samples");
    write_file(dir / "scene.in", text);
    const Scene scene = parse_scene(text);
    struct Case {
        std::string arguments;
        ImageEncoding encoding;
        RenderOptions options;
    };
    std::vector<Case> cases;
    for (const ImageFormat format : {ImageFormat::ppm, ImageFormat::png})
        for (const int bits : {8, 16})
            for (const Gamma& gamma : kGammas)
                for (const RenderOptions& options : option_sets()) {
                    Case c{"--bits " + std::to_string(bits) + " --gamma " + gamma_name(gamma),
                           {},
                           options};
                    c.encoding.format = format;
                    c.encoding.bits = bits;
                    c.encoding.gamma = gamma;
                    if (options.adaptive_threshold)
                        c.arguments += " -a 0.02 -s 3";
                    else if (options.samples == 2)
                        c.arguments += " -s 2";
                    cases.push_back(c);
                }
    for (const Case& c : cases) {
        const std::string file = std::string("out.") + format_name(c.encoding.format);
        const RunResult r =
            run_rt(dir, "--no-metadata -j 3 " + c.arguments + " scene.in -o " + file);
        CHECK_EQ(r.status, 0);
        if (read_file(dir / file) != encode_image(render(scene, c.options), c.encoding))
            record_failure(__FILE__, __LINE__, join(file, " with ", c.arguments, " differs"));
    }
}
