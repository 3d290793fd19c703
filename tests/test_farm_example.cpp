// docs/examples/farm works as its README says: the strips of a sphere-light scene, rendered
// by local.sh (xargs -P) and merged by rtimg, are the whole render byte for byte; where
// Slurm is installed and a cluster answers, submit.sh's job array does the same, also when
// one of its tasks is requeued while it renders (and resumes from its checkpoint).
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
    join("RT='", RT_BINARY, "' RTIMG='", RTIMG_BINARY, "' RTFLAGS='--size 96x64 -a 0.02 -q' ");

bool cluster_answers() {
    if (shell("command -v sbatch >/dev/null 2>&1 && sinfo -h >/dev/null 2>&1") == 0) return true;
    std::cout << "SKIPPED: no Slurm cluster answers here (sbatch, sinfo): the job array is not "
                 "checked (docs/examples/farm/start-cluster.sh starts one)\n";
    return false;
}

// What `command` prints on standard output.
std::string output_of(const fs::path& dir, const std::string& command) {
    const fs::path out = dir / "command.out";
    shell(join(command, " >'", out.string(), "' 2>/dev/null"));
    return read_file(out);
}

// Waits (up to 5 minutes) for a job to leave the queue.
void wait_for_job(const std::string& id) {
    for (int i = 0; i < 300; ++i) {
        if (shell(join("squeue -h -j ", id, " 2>/dev/null | grep -q .")) != 0) return;
        std::this_thread::sleep_for(std::chrono::seconds(1));
    }
}

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
    if (!cluster_answers()) return;
    const fs::path dir = work_dir("farm-slurm");
    const fs::path id_file = dir / "merge-job.txt";
    CHECK_EQ(
        shell(join("cd '", dir.string(), "' && ", kEnvironment, "'", (kFarm / "submit.sh").string(),
                   "' '", kScene, "' 4 '", (dir / "strips").string(), "' '",
                   (dir / "merged.png").string(), "' >'", id_file.string(), "'")),
        0);
    wait_for_job(read_file(id_file).substr(0, read_file(id_file).find('\n')));
    CHECK(read_file(dir / "merged.png") == whole_render(dir));
}

// A strip requeued while it renders (as a preemption does: SIGTERM, then the task back in the
// queue) flushes its checkpoint, runs again, resumes, and the merge is still the whole
// render, byte for byte.
TEST(a_requeued_strip_resumes_and_the_merge_is_the_whole_render) {
    if (!cluster_answers()) return;
    const fs::path dir = work_dir("farm-requeue");
    const std::string flags = "--size 128x128 -s 6";
    const std::string merge = output_of(
        dir, join("cd '", dir.string(), "' && RT='", RT_BINARY, "' RTIMG='", RTIMG_BINARY,
                  "' RTFLAGS='", flags, "' '", (kFarm / "submit.sh").string(), "' '", kScene,
                  "' 2 '", (dir / "strips").string(), "' '", (dir / "merged.png").string(), "'"));
    const std::string merge_id = merge.substr(0, merge.find('\n'));
    // The array's id, from the merge's dependency ("afterok:12_*(unfulfilled)").
    const std::string shown = output_of(dir, "scontrol show job " + merge_id);
    const std::size_t after = shown.find("afterok:");
    CHECK(after != std::string::npos);
    const std::string array = shown.substr(after + 8, shown.find('_', after) - after - 8);
    const std::string task = array + "_0";
    // Task 0 has finished a few rows (its header and five rows of 3,098 bytes): requeue it.
    const fs::path checkpoint = dir / "strips" / "strip-0-of-2.ck";
    const auto rows_kept = [&] {
        std::error_code ec;
        const std::uintmax_t size = fs::file_size(checkpoint, ec);
        return !ec && size >= 700 + 5 * 3098;
    };
    for (int i = 0; i < 3000 && !rows_kept(); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    CHECK_EQ(shell("scontrol requeue " + task), 0);
    // Slurm holds a requeued task back for two minutes: let it start again at once.
    for (int i = 0; i < 100; ++i) {
        if (output_of(dir, "squeue -h -j " + task + " -o %t").find("R") == 0) break;
        shell("scontrol update jobid=" + task + " StartTime=now >/dev/null 2>&1");
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
    }
    wait_for_job(merge_id);
    const std::string log = read_file(dir / "strips" / ("slurm-" + task + ".out"));
    CHECK_CONTAINS(log, "rt: interrupted");
    CHECK_CONTAINS(log, "rt: resuming from '" + checkpoint.string() + "'");
    CHECK(!fs::exists(checkpoint));
    CHECK(run_rt(dir, join("-q ", flags, " -o whole.png '", kScene, "'")).status == 0);
    CHECK(read_file(dir / "merged.png") == read_file(dir / "whole.png"));
}
