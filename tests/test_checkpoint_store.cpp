// The checkpoint store under a real render, in one process: a complete checkpoint damaged at
// every byte, and cut at every byte, is resumed; each time the raster is the uninterrupted
// one bit for bit, exactly the complete records before the damage are taken from the file,
// and the file ends whole again (its damaged tail cut off, the missing rows appended). A
// file whose first line is damaged is no checkpoint: refused, and left as it was.
#include <unistd.h>

#include <filesystem>
#include <string>

#include "batch/checkpoint.h"
#include "batch/checkpoint_store.h"
#include "check.h"
#include "cli_util.h"
#include "rt/error.h"
#include "rt/render.h"
#include "scene_util.h"

using namespace rt_test;
namespace fs = std::filesystem;

namespace {

const char* const kScene =
    "102  0 1 6  0 0 0  0.5 0 0  0 0.4 0  6 4\n103 0.2 0.2 0.2\n101 3 4 5 1 1 1\n"
    "1 1  0 0 0  100 0.9 0.3 0.2  0.3 20 0.6 0.2 1.5\n"
    "2 -1  0 1 0  107 0.7  100 1 1 1 0 1 0.8 0 1  100 0.2 0.2 0.2 0 1 0.8 0 1\n";

rt::CheckpointPlan plan_for(const fs::path& path, const rt::RenderOptions& options,
                            const rt::Scene& scene) {
    rt::CheckpointPlan plan;
    plan.path = path.string();
    plan.header = {{"version", "test"}, {"adaptive", options.adaptive_threshold ? "on" : "off"}};
    plan.resume = true;
    plan.quiet = true;
    plan.rows = rt::image_rect(scene.viewer);
    if (options.adaptive_threshold) plan.one_ray_rows = plan.rows;  // the margin is outside
    return plan;
}

// Where each record of a complete checkpoint ends: the header's first, then each row's.
std::vector<std::size_t> record_ends(const std::string& bytes) {
    std::vector<std::size_t> ends;
    std::size_t at = rt::kCheckpointMagic.size();
    while (at < bytes.size()) {
        std::uint32_t length = 0;
        for (int i = 0; i < 4; ++i)
            length |= std::uint32_t{static_cast<unsigned char>(bytes[at + 5 + i])} << (8 * i);
        at += 4 + 1 + 4 + length + 4;
        ends.push_back(at);
    }
    return ends;
}

// Thousands of checkpoints are made here, each synced to disk: in memory (/dev/shm) where
// there is such a file system, so that the test waits for no disk.
fs::path scratch_dir(const std::string& name) {
    std::error_code ec;
    if (!fs::is_directory("/dev/shm", ec)) return work_dir(name);
    const fs::path dir =
        fs::path("/dev/shm") / ("rt-test-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(dir, ec);
    fs::create_directories(dir);
    return dir;
}

void check_every_damage(const rt::RenderOptions& options, const std::string& name) {
    const fs::path dir = scratch_dir(name);
    const fs::path path = dir / "c.ck";
    const rt::Scene scene = parse_scene(kScene);
    const rt::Raster expected = rt::render(scene, options);
    // A complete checkpoint: every row of every pass.
    rt::CheckpointPlan fresh = plan_for(path, options, scene);
    fresh.resume = false;
    {
        rt::CheckpointStore store(fresh, nullptr);
        CHECK(identical(rt::render_region(scene, options, fresh.rows, nullptr, nullptr, &store),
                        expected));
    }
    const std::string full = read_file(path);
    const std::vector<std::size_t> ends = record_ends(full);
    const std::size_t rows = ends.size() - 1;
    CHECK_EQ(rows, static_cast<std::size_t>(options.adaptive_threshold ? 8 : 4));
    CHECK_EQ(ends.back(), full.size());
    // The rows whose records end by byte `i`; none when the header does not.
    const auto rows_before = [&](std::size_t i) {
        std::size_t n = 0;
        for (std::size_t k = 1; k < ends.size(); ++k)
            if (ends[k] <= i && ends[0] <= i) ++n;
        return n;
    };
    int refused = 0;
    for (int cut = 0; cut < 2; ++cut) {
        for (std::size_t i = 0; i < full.size(); ++i) {
            std::string bytes = full;
            if (cut == 1) {
                bytes.resize(i);
            } else {
                bytes[i] = static_cast<char>(bytes[i] ^ 0x24);
            }
            write_file(path, bytes);
            if (i < rt::kCheckpointMagic.size()) {
                // Not recognisably a checkpoint: refused, never written over.
                CHECK_CONTAINS(rt_test::error_of([&] {
                                   rt::CheckpointStore store(plan_for(path, options, scene),
                                                             nullptr);
                               }),
                               "c.ck: it is not an rt checkpoint");
                CHECK(read_file(path) == bytes);
                ++refused;
                continue;
            }
            // Damage at i spoils the record holding i, a cut at i the one it falls in: the
            // records before it are kept (none when it is the header).
            const std::size_t expected_rows = rows_before(i);
            rt::CheckpointStore store(plan_for(path, options, scene), nullptr);
            const rt::Raster got =
                rt::render_region(scene, options, fresh.rows, nullptr, nullptr, &store);
            CHECK(identical(got, expected));
            CHECK_EQ(store.rows_resumed(), expected_rows);
            // Whole again: what was kept, then every missing row.
            const rt::CheckpointContents after = rt::read_checkpoint(read_file(path));
            CHECK(!after.damaged);
            CHECK_EQ(after.rows.size(), rows);
        }
    }
    CHECK_EQ(refused, 2 * static_cast<int>(rt::kCheckpointMagic.size()));
    std::error_code ec;
    fs::remove_all(dir, ec);
}

}  // namespace

TEST(a_checkpoint_damaged_or_cut_at_any_byte_resumes_to_the_same_raster) {
    check_every_damage(rt::RenderOptions{}, "store_damage");
}

TEST(so_does_one_with_both_passes_of_adaptive_supersampling) {
    rt::RenderOptions options;
    options.adaptive_threshold = 0.05;
    options.samples = 2;
    check_every_damage(options, "store_damage_adaptive");
}
