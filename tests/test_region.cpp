// Regions (--region): every pixel of a region is the same pixel of the whole render, bit for
// bit, on every scene, with supersampling, adaptive supersampling and any thread count; the
// command line checks the bounds and records the region in the file.
#include <algorithm>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <vector>

#include "check.h"
#include "cli_util.h"
#include "rt/reader.h"
#include "rt/render.h"

namespace fs = std::filesystem;
using namespace rt;
using namespace rt_test;

namespace {

std::vector<fs::path> scene_files() {
    return files_with_extension(fs::path(RT_SOURCE_DIR) / "scenes", ".in");
}

// Whether `part` holds exactly the pixels of `whole` at `rect`.
bool same_pixels(const Raster& whole, const Raster& part, const PixelRect& rect) {
    if (part.width() != rect.width() || part.height() != rect.height()) return false;
    for (int y = rect.y0; y < rect.y1; ++y)
        for (int x = rect.x0; x < rect.x1; ++x)
            if (!(whole.at(x, y) == part.at(x - rect.x0, y - rect.y0))) return false;
    return true;
}

// Random regions of a w x h image, with 1-pixel-wide and 1-pixel-high ones among them.
std::vector<PixelRect> random_regions(std::mt19937& random, int w, int h) {
    const auto pick = [&](int n) { return std::uniform_int_distribution<int>(0, n - 1)(random); };
    std::vector<PixelRect> regions;
    for (int i = 0; i < 3; ++i) {
        const int x0 = pick(w), y0 = pick(h);
        regions.push_back({x0, y0, x0 + 1 + pick(w - x0), y0 + 1 + pick(h - y0)});
    }
    const int x = pick(w), y = pick(h);
    regions.push_back({x, 0, x + 1, h});      // one column
    regions.push_back({0, y, w, y + 1});      // one row
    regions.push_back({w - 1, h - 1, w, h});  // the last pixel
    return regions;
}

void check_regions(const Scene& scene, RenderOptions options, std::mt19937& random,
                   const std::string& what) {
    options.threads = 2;
    const Raster whole = render(scene, options);
    for (const PixelRect& r : random_regions(random, scene.viewer.xres, scene.viewer.yres)) {
        options.threads = 1 + static_cast<int>(random() % 3);
        if (!same_pixels(whole, render_region(scene, options, r), r))
            record_failure(__FILE__, __LINE__,
                           join(what, ": region ", r.x0, ",", r.x1, ",", r.y0, ",", r.y1, " on ",
                                options.threads, " threads differs from the whole render"));
    }
}

// The scene at no more than 48 pixels a side (as --size would), so that every scene is quick.
Scene small_scene(const fs::path& file) {
    Scene scene = read_scene_file(file.string());
    const double shrink = std::min(1.0, 48.0 / std::max(scene.viewer.xres, scene.viewer.yres));
    scene.viewer.xres = std::max(1, static_cast<int>(scene.viewer.xres * shrink));
    scene.viewer.yres = std::max(1, static_cast<int>(scene.viewer.yres * shrink));
    return scene;
}

}  // namespace

TEST(regions_of_every_scene_equal_the_whole_render) {
    std::mt19937 random(10);
    for (const fs::path& file : scene_files()) {
        const Scene scene = small_scene(file);
        RenderOptions plain;
        check_regions(scene, plain, random, file.filename().string());
        RenderOptions adaptive;
        adaptive.adaptive_threshold = 0.02;
        adaptive.samples = 3;
        check_regions(scene, adaptive, random, file.filename().string() + " -a 0.02");
    }
}

TEST(regions_of_the_sphere_light_scene_at_full_size_equal_the_whole_render) {
    // Its samples are hashed from the lit point: a region must trace exactly the same rays.
    const Scene scene = read_scene_file(std::string(RT_SOURCE_DIR) + "/scenes/sphere-light.in");
    std::mt19937 random(110);
    check_regions(scene, {}, random, "sphere-light.in");
    RenderOptions supersampled;
    supersampled.samples = 2;
    check_regions(scene, supersampled, random, "sphere-light.in -s 2");
    RenderOptions adaptive;
    adaptive.adaptive_threshold = 0.01;
    adaptive.samples = 3;
    check_regions(scene, adaptive, random, "sphere-light.in -a 0.01");
}

TEST(an_empty_region_or_one_outside_the_image_is_refused) {
    const Scene scene = small_scene(fs::path(RT_SOURCE_DIR) / "scenes" / "sphere.in");
    for (const PixelRect& bad : {PixelRect{0, 0, 0, 1}, PixelRect{0, 0, scene.viewer.xres + 1, 1},
                                 PixelRect{-1, 0, 1, 1}}) {
        bool threw = false;
        try {
            render_region(scene, {}, bad);
        } catch (const std::invalid_argument&) {
            threw = true;
        }
        CHECK(threw);
    }
}

TEST(the_command_line_checks_the_bounds) {
    const fs::path dir = work_dir("region-cli");
    write_file(dir / "small.in", kSmallScene);  // 8 x 6
    for (const char* bad : {"0,0,0,1", "3,2,0,1", "0,1,1,1", "0,1,2", "0,1,2,3,4", "a,1,2,3",
                            "-1,1,0,1", "0,1,0,1,", "0, 1,0,1"}) {
        const RunResult r = run_rt(dir, join("--region '", bad, "' small.in -o x.ppm"));
        CHECK_EQ(r.status, 2);
        CHECK_CONTAINS(r.err, "--region");
    }
    for (const char* outside : {"0,9,0,1", "0,8,0,7", "8,9,0,1"}) {
        const RunResult r = run_rt(dir, join("--region ", outside, " small.in -o x.ppm"));
        CHECK_EQ(r.status, 2);
        CHECK_CONTAINS(r.err, "is outside the 8x6 image");
    }
    const RunResult pfm = run_rt(dir, "--region 0,1,0,1 small.in -o x.pfm");
    CHECK_EQ(pfm.status, 2);
    CHECK_CONTAINS(pfm.err, "PFM");
    CHECK(!fs::exists(dir / "x.pfm"));
}

TEST(a_region_file_records_the_region_and_the_full_size) {
    const fs::path dir = work_dir("region-file");
    write_file(dir / "small.in", kSmallScene);
    CHECK_EQ(run_rt(dir, "--region 2,5,1,6 small.in -o part.ppm").status, 0);
    const std::string part = read_file(dir / "part.ppm");
    CHECK_CONTAINS(part, "# Region: 2,5,1,6\n# Full-Size: 8x6\n3 5\n255\n");
    // The options are those of the whole render, so that a merge can write its metadata.
    CHECK_EQ(run_rt(dir, "small.in -o whole.ppm").status, 0);
    const std::string whole = read_file(dir / "whole.ppm");
    CHECK_EQ(part.substr(0, part.find("# Region")), whole.substr(0, whole.find("8 6\n")));
    // --no-metadata leaves out what made the image, but not what a merge needs.
    CHECK_EQ(run_rt(dir, "--no-metadata --region 2,5,1,6 small.in -o bare.ppm").status, 0);
    CHECK_EQ(read_file(dir / "bare.ppm").substr(0, 40),
             std::string("P6\n# Region: 2,5,1,6\n# Full-Size: 8x6\n3 5").substr(0, 40));
}
