// docs/examples/farm works as its README says: the strips of a sphere-light scene, rendered
// by local.sh (xargs -P) and merged by rtimg, are the whole render byte for byte; where
// Slurm is installed and a cluster answers, submit.sh's job array does the same.
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include "check.h"
#include "cli_util.h"

namespace fs = std::filesystem;
using namespace rt_test;

namespace {

const fs::path kFarm = fs::path(RT_SOURCE_DIR) / "docs" / "examples" / "farm";
const std::string kScene = std::string(RT_SOURCE_DIR) + "/scenes/sphere-light.in";
const std::string kEnvironment =
    join("RT='", RT_BINARY, "' RTIMG='", RTIMG_BINARY, "' RTFLAGS='--size 96x64 -a 0.02' ");

// The whole render with the strips' options, to compare with.
std::string whole_render(const fs::path& dir) {
    CHECK_EQ(run_rt(dir, join("-q --size 96x64 -a 0.02 -o whole.png '", kScene, "'")).status, 0);
    return read_file(dir / "whole.png");
}

}  // namespace

TEST(local_strips_merge_into_the_whole_render) {
    if (!on_path("xargs")) {
        std::cout << "xargs is not installed: not checked\n";
        return;
    }
    const fs::path dir = work_dir("farm-local");
    const fs::path log = dir / "local.log";
    // 7 strips of 64 rows: 9 or 10 rows each.
    CHECK_EQ(
        shell(join("cd '", dir.string(), "' && ", kEnvironment, "JOBS=3 '",
                   (kFarm / "local.sh").string(), "' '", kScene, "' 7 '", (dir / "strips").string(),
                   "' '", (dir / "merged.png").string(), "' >'", log.string(), "' 2>&1")),
        0);
    CHECK_EQ(read_file(log), "");
    CHECK(fs::exists(dir / "strips" / "strip-6-of-7.png"));
    CHECK(read_file(dir / "merged.png") == whole_render(dir));
    // Again into the same directory with fewer strips: the old ones are not mixed in.
    CHECK_EQ(
        shell(join("cd '", dir.string(), "' && ", kEnvironment, "JOBS=3 '",
                   (kFarm / "local.sh").string(), "' '", kScene, "' 3 '", (dir / "strips").string(),
                   "' '", (dir / "merged3.png").string(), "' >'", log.string(), "' 2>&1")),
        0);
    CHECK_EQ(read_file(log), "");
    CHECK(read_file(dir / "merged3.png") == whole_render(dir));
}

// A scene rt cannot read: one message, rt's own, and a failing status; no strip starts.
TEST(a_bad_scene_fails_once_with_rts_message) {
    if (!on_path("xargs")) {
        std::cout << "xargs is not installed: not checked\n";
        return;
    }
    const fs::path dir = work_dir("farm-bad");
    const fs::path log = dir / "local.log";
    CHECK(
        shell(join("cd '", dir.string(), "' && ", kEnvironment, "'", (kFarm / "local.sh").string(),
                   "' nonexistent.in 2 strips out.png >'", log.string(), "' 2>&1")) != 0);
    CHECK_EQ(read_file(log), std::string("nonexistent.in: cannot open scene file: No such file "
                                         "or directory\n"));
    CHECK(!fs::exists(dir / "strips"));
    // strip.sh alone, as a farm job runs it, fails with the same message, not a --region one.
    CHECK(
        shell(join("cd '", dir.string(), "' && ", kEnvironment, "'", (kFarm / "strip.sh").string(),
                   "' nonexistent.in 2 0 . >'", log.string(), "' 2>&1")) != 0);
    CHECK_EQ(read_file(log), std::string("nonexistent.in: cannot open scene file: No such file "
                                         "or directory\n"));
}

TEST(slurm_strips_merge_into_the_whole_render_where_a_cluster_runs) {
    if (shell("command -v sbatch >/dev/null 2>&1 && sinfo -h >/dev/null 2>&1") != 0) {
        std::cout << "SKIPPED: no Slurm cluster answers here (sbatch, sinfo): the job array "
                     "is not checked\n";
        return;
    }
    const fs::path dir = work_dir("farm-slurm");
    const fs::path id_file = dir / "merge-job.txt";
    CHECK_EQ(
        shell(join("cd '", dir.string(), "' && ", kEnvironment, "'", (kFarm / "submit.sh").string(),
                   "' '", kScene, "' 4 '", (dir / "strips").string(), "' '",
                   (dir / "merged.png").string(), "' >'", id_file.string(), "'")),
        0);
    // Wait (up to 5 minutes) for the merge job to leave the queue.
    const std::string id = read_file(id_file).substr(0, read_file(id_file).find('\n'));
    for (int i = 0; i < 300; ++i) {
        if (shell(join("squeue -h -j ", id, " 2>/dev/null | grep -q .")) != 0) break;
        std::this_thread::sleep_for(std::chrono::seconds(1));
    }
    CHECK(read_file(dir / "merged.png") == whole_render(dir));
}
