// The render's row store (what --checkpoint builds on): a render hands every row it finishes
// to the store, once per pass; one given rows takes them instead of tracing them, and the
// raster is bit for bit the one an uninterrupted render makes, whatever rows it had, with
// adaptive supersampling, regions and any number of threads, and so are its samples.
#include <algorithm>
#include <map>
#include <mutex>
#include <random>
#include <tuple>
#include <vector>

#include "check.h"
#include "rt/reader.h"
#include "rt/render.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

const char* const kScene =
    "102  0 0.5 4  0 0 0  0.5 0 0  0 0.4 0  40 32\n103 0.1 0.1 0.1\n"
    "110 4 -3 4 4 0.5 30 30 30\n"
    "1 1  0 0 0  100 0.8 0.3 0.2  0.3 20 0.6 0 1\n"
    "1 0.5  1.2 0.2 1  114 1 1 1 0.1 50 0 1.5 0 0 0\n"
    "2 -1  0 1 0  107 0.5 100 0.9 0.9 0.9 0 1 0.8 0 1 100 0.2 0.2 0.3 0 1 0.8 0 1\n";

// Rows by (pass, y, x0, x1), as a checkpoint would keep them.
class MemoryStore : public RowStore {
  public:
    using Key = std::tuple<int, int, int, int>;
    bool restore(int pass, int y, int x0, int x1, double* values) override {
        const std::lock_guard lock(mutex_);
        const auto it = held.find({pass, y, x0, x1});
        if (it == held.end()) return false;
        std::copy(it->second.begin(), it->second.end(), values);
        ++restored;
        return true;
    }
    void finished(int pass, int y, int x0, int x1, const double* values) override {
        const std::lock_guard lock(mutex_);
        const std::size_t n = static_cast<std::size_t>(x1 - x0) * kSpectrumComponents;
        CHECK(handed.find({pass, y, x0, x1}) == handed.end());  // each row once
        handed[{pass, y, x0, x1}].assign(values, values + n);
    }
    std::map<Key, std::vector<double>> held, handed;
    int restored = 0;

  private:
    std::mutex mutex_;
};

RenderOptions with(int threads, bool adaptive) {
    RenderOptions options;
    options.threads = threads;
    if (adaptive) {
        options.samples = 3;
        options.adaptive_threshold = 0.05;
    }
    return options;
}

}  // namespace

TEST(every_row_is_handed_to_the_store_once_per_pass) {
    const Scene scene = parse_scene(kScene);
    for (const bool adaptive : {false, true}) {
        MemoryStore store;
        const Raster plain = render(scene, with(1, adaptive));
        const Raster stored = render_region(scene, with(3, adaptive), image_rect(scene.viewer),
                                            nullptr, nullptr, &store);
        CHECK(identical(plain, stored));
        // One row per pass and y, whole width; the one-ray pass only with -a.
        CHECK_EQ(store.handed.size(), adaptive ? 64u : 32u);
        int final_rows = 0;
        for (const auto& [key, values] : store.handed) {
            const auto [pass, y, x0, x1] = key;
            CHECK(pass == 1 || (adaptive && pass == 0));
            final_rows += pass == 1 ? 1 : 0;
            CHECK(x0 == 0 && x1 == 40);
            // A final row holds the pixels of the image.
            if (pass == 1)
                for (int x = x0; x < x1; ++x)
                    CHECK(plain.at(x, y)[1] == values[static_cast<std::size_t>(x) * 3 + 1]);
        }
        CHECK_EQ(final_rows, 32);
    }
}

// Any subset of the rows of a first run, restored: the same bits, fewer rays, every row
// counted as done.
TEST(a_render_resumed_from_any_rows_is_the_uninterrupted_one) {
    const Scene scene = parse_scene(kScene);
    std::mt19937 random(20261201);
    for (const bool adaptive : {false, true})
        for (const PixelRect region : {image_rect(scene.viewer), PixelRect{5, 3, 31, 20}}) {
            MemoryStore first;
            const Raster whole =
                render_region(scene, with(2, adaptive), region, nullptr, nullptr, &first);
            for (int trial = 0; trial < 4; ++trial) {
                MemoryStore resumed;
                for (const auto& [key, values] : first.handed)
                    if (std::uniform_int_distribution<int>(0, 2)(random) != 0)
                        resumed.held[key] = values;
                RenderStats stats, full_stats;
                RenderProgress progress;
                const Raster again = render_region(scene, with(1 + trial, adaptive), region, &stats,
                                                   &progress, &resumed);
                CHECK(identical(whole, again));
                CHECK_EQ(resumed.restored, static_cast<int>(resumed.held.size()));
                CHECK_EQ(resumed.held.size() + resumed.handed.size(), first.handed.size());
                CHECK_EQ(progress.rows_done.load(), progress.rows_total.load());
                render_region(scene, with(1, adaptive), region, &full_stats);
                if (!resumed.held.empty()) CHECK(stats.total() < full_stats.total());
                // Kept as samples (rt's PPM and PNG): the same rows restored, the samples of
                // the uninterrupted raster.
                MemoryStore resumed_samples;
                resumed_samples.held = resumed.held;
                const Gamma srgb{Gamma::Kind::srgb, 1};
                const SampleRaster samples =
                    render_region_samples(scene, with(2 + trial, adaptive), region, 16, srgb,
                                          nullptr, nullptr, &resumed_samples);
                const SampleImage expected = quantize(whole, 16, srgb);
                CHECK(std::equal(samples.bytes().begin(), samples.bytes().end(),
                                 expected.bytes.begin(), expected.bytes.end()));
                CHECK_EQ(resumed_samples.restored, resumed.restored);
                CHECK(resumed_samples.handed == resumed.handed);
            }
        }
}

// What a store gives is what the image gets: restored rows are not traced again.
TEST(restored_rows_are_taken_as_they_are) {
    const Scene scene = parse_scene(kScene);
    MemoryStore store;
    store.held[{1, 7, 0, 40}] = std::vector<double>(120, 0.25);
    const Raster image =
        render_region(scene, with(2, false), image_rect(scene.viewer), nullptr, nullptr, &store);
    for (int x = 0; x < 40; ++x) CHECK(image.at(x, 7) == Spectrum(0.25));
    CHECK(!(image.at(20, 8) == Spectrum(0.25)));
}
