// Golden images: every scene in scenes/ renders, and matches its image in tests/golden/
// within a small tolerance. Goldens catch regressions; the other tests prove correctness.
//
// The comparison is rtimg diff's (rt::compare_images): a failing scene leaves its render and
// a heat map in build/tests/work/golden/, and the message says where.
// To regenerate after an intended change, run:  build/tests/test_golden --update
// and look at the new images before committing them.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "check.h"
#include "cli_util.h"
#include "rt/image_compare.h"
#include "rt/image_io.h"
#include "rt/reader.h"
#include "rt/render.h"

namespace fs = std::filesystem;

namespace {

// A pixel "differs" when a component is more than this many levels (of 255) away: slack for
// a C library whose pow, exp or sqrt rounds differently (docs/rtimg.md, SAME BYTES). Builds
// with g++ and clang on one machine give the same bytes (.ci/compare-compilers).
constexpr double kLevelTolerance = 2;
// Pixels on an edge may flip between two objects; allow this fraction of them to differ.
constexpr double kDifferingPixelFraction = 0.002;

const fs::path kScenes = fs::path(RT_SOURCE_DIR) / "scenes";
const fs::path kGolden = fs::path(RT_SOURCE_DIR) / "tests" / "golden";

std::vector<fs::path> scene_files() { return rt_test::files_with_extension(kScenes, ".in"); }

std::string render_to_ppm(const fs::path& scene_file) {
    const rt::Scene scene = rt::read_scene_file(scene_file.string());
    std::ostringstream out;
    out << rt::encode_image(rt::render(scene, {}), {});
    return out.str();
}

bool update_mode() {
    const auto& args = rt_test::arguments();
    return std::find(args.begin(), args.end(), "--update") != args.end();
}

}  // namespace

TEST(every_scene_matches_its_golden_image) {
    const auto files = scene_files();
    CHECK(files.size() >= 7);
    for (const fs::path& file : files) {
        const fs::path golden = kGolden / (file.stem().string() + ".ppm");
        std::string image;
        try {
            image = render_to_ppm(file);
        } catch (const std::exception& e) {
            rt_test::record_failure(__FILE__, __LINE__, rt_test::join(file, ": ", e.what()));
            continue;
        }
        if (update_mode()) {
            fs::create_directories(kGolden);
            std::ofstream(golden, std::ios::binary) << image;
            std::cout << "updated " << golden << "\n";
            continue;
        }
        if (!fs::exists(golden)) {
            rt_test::record_failure(__FILE__, __LINE__,
                                    rt_test::join(golden, " is missing: run test_golden --update"));
            continue;
        }
        const rt::ImageFile expected = rt::read_image_file(golden);
        const rt::ImageFile actual = rt::decode_image(image);
        const fs::path failures = fs::path(RT_TEST_WORK_DIR) / "golden";
        const std::string stem = file.stem().string();
        if (expected.width() != actual.width() || expected.height() != actual.height()) {
            fs::create_directories(failures);
            std::ofstream(failures / (stem + ".ppm"), std::ios::binary) << image;
            rt_test::record_failure(__FILE__, __LINE__,
                                    rt_test::join(file, ": size changed; the render is in ",
                                                  failures / (stem + ".ppm")));
            continue;
        }
        const rt::ImageDifference d = rt::compare_images(actual, expected, kLevelTolerance);
        std::cout << "  " << file.filename().string() << ": " << d.differing
                  << " pixels differ, worst " << d.largest << " levels\n";
        if (d.fraction() > kDifferingPixelFraction) {
            // Left for a person to look at: what rendered, and where it differs.
            fs::create_directories(failures);
            const fs::path rendered = failures / (stem + ".ppm");
            const fs::path heat = failures / (stem + "-diff.png");
            std::ofstream(rendered, std::ios::binary) << image;
            std::ofstream(heat, std::ios::binary)
                << rt::encode_png(rt::heat_map(actual, expected, kLevelTolerance), {});
            rt_test::record_failure(
                __FILE__, __LINE__,
                rt_test::join(file, ": ", d.differing,
                              " pixels differ from the golden image by more than ", kLevelTolerance,
                              " levels (largest ", d.largest, "); the render is ", rendered,
                              ", the heat map ", heat, "; compare with: rtimg diff --tolerance ",
                              kLevelTolerance, " --max-fraction ", kDifferingPixelFraction, " ",
                              rendered, " ", golden));
        }
    }
}
