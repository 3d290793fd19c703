// Golden images: every scene in scenes/ renders, and matches its image in tests/golden/
// within a small tolerance. Goldens catch regressions; the other tests prove correctness.
//
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
#include "rt/ppm.h"
#include "rt/reader.h"
#include "rt/trace.h"

namespace fs = std::filesystem;

namespace {

// A pixel "differs" when a component is more than this many levels (of 255) away: slack for
// floating-point differences between compilers.
constexpr int kLevelTolerance = 2;
// Pixels on an edge may flip between two objects; allow this fraction of them to differ.
constexpr double kDifferingPixelFraction = 0.002;

const fs::path kScenes = fs::path(RT_SOURCE_DIR) / "scenes";
const fs::path kGolden = fs::path(RT_SOURCE_DIR) / "tests" / "golden";

std::vector<fs::path> scene_files() {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(kScenes))
        if (entry.path().extension() == ".in") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

std::string render_to_ppm(const fs::path& scene_file) {
    const rt::Scene scene = rt::read_scene_file(scene_file.string());
    std::ostringstream out;
    rt::write_ppm(out, rt::render(scene, {}));
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
        const rt::Image expected = rt::read_ppm(golden);
        const rt::Image actual = [&] {
            const fs::path tmp = fs::path(RT_TEST_WORK_DIR) / "golden-actual.ppm";
            std::ofstream(tmp, std::ios::binary) << image;
            return rt::read_ppm(tmp);
        }();
        if (expected.width != actual.width || expected.height != actual.height) {
            rt_test::record_failure(__FILE__, __LINE__, rt_test::join(file, ": size changed"));
            continue;
        }
        std::size_t differing = 0;
        double worst = 0;
        for (std::size_t p = 0; p < actual.values.size(); p += 3) {
            double diff = 0;
            for (std::size_t c = 0; c < 3; ++c)
                diff = std::max(diff, std::fabs(static_cast<double>(actual.values[p + c]) -
                                                static_cast<double>(expected.values[p + c])));
            worst = std::max(worst, diff);
            if (diff * 255 > kLevelTolerance + 0.5) ++differing;
        }
        const double fraction =
            static_cast<double>(differing) * 3 / static_cast<double>(actual.values.size());
        std::cout << "  " << file.filename().string() << ": " << differing
                  << " pixels differ, worst " << worst * 255 << " levels\n";
        if (fraction > kDifferingPixelFraction)
            rt_test::record_failure(
                __FILE__, __LINE__,
                rt_test::join(file, ": ", differing, " pixels differ from the golden image"));
    }
}
