// rt --checkpoint and --resume through the real binary: a render stopped part way (killed,
// or ended by SIGTERM) and resumed writes exactly the bytes of an uninterrupted render, in
// every format, with -s, -a and --region, on other thread counts; a checkpoint of another
// render is refused with what differs and left as it was; the output is never harmed; a
// full disk costs the checkpoint, not the render.
#include <csignal>
#include <string>
#include <vector>

#include "batch/checkpoint.h"
#include "check.h"
#include "cli_util.h"
#include "process_util.h"
#include "resume_util.h"

using namespace rt_test;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
    args.insert(args.end(), more.begin(), more.end());
    return args;
}

// The image an uninterrupted render of `args` (which write `output`) gives.
std::string uninterrupted(const fs::path& dir, const std::vector<std::string>& args,
                          const std::string& output) {
    const RunResult r = run_rt_args(dir, with({"scene.in"}, args));
    CHECK_EQ(r.status, 0);
    std::string bytes = read_file(dir / output);
    fs::remove(dir / output);
    CHECK(!bytes.empty());
    return bytes;
}

// The rows of a checkpoint, each with its width.
struct Rows {
    int count = 72;
    int width = 96;
    int one_ray_count = 0;  // -a's one-ray pass, over the region and its margin
    int one_ray_width = 0;
};

// About `share` of what a checkpoint holds once complete: its header (about 700 bytes), then
// rows of 26 + 24 x width bytes.
std::uintmax_t bytes_at(double share, const Rows& rows = {}) {
    const double all = rows.count * (26.0 + 24 * rows.width) +
                       rows.one_ray_count * (26.0 + 24 * rows.one_ray_width);
    return 700 + static_cast<std::uintmax_t>(share * all);
}

// Stops a checkpointing render of `args` at about `share`, and checks what that left: no
// image, and a checkpoint with some rows.
void stop_part_way(const fs::path& dir, const std::vector<std::string>& args, double share,
                   int sig = SIGKILL, const Rows& rows = {}) {
    const int status = stop_at_size(dir, with({"scene.in", "--checkpoint", "c.ck"}, args),
                                    dir / "c.ck", bytes_at(share, rows), sig);
    CHECK(WIFSIGNALED(status) && WTERMSIG(status) == sig);
    CHECK(fs::exists(dir / "c.ck"));
    CHECK(!checkpoint_in(dir / "c.ck").rows.empty());
}

RunResult resume(const fs::path& dir, const std::vector<std::string>& args) {
    return run_rt_args(dir, with({"scene.in", "--checkpoint", "c.ck", "--resume"}, args));
}

}  // namespace

TEST(a_resumed_render_writes_the_bytes_of_an_uninterrupted_one_in_every_format_and_mode) {
    const fs::path dir = resume_dir("resume_formats");
    struct Case {
        std::vector<std::string> args;
        std::string output;
        Rows rows;
    };
    const Case cases[] = {
        {{"-o", "out.ppm"}, "out.ppm", {}},
        {{"-o", "out.png", "--bits", "16", "--gamma", "srgb"}, "out.png", {}},
        {{"-o", "out.pfm"}, "out.pfm", {}},
        {{"-s", "2", "-o", "out.png"}, "out.png", {}},
        {{"-a", "0.05", "-o", "out.png"}, "out.png", {72, 96, 72, 96}},
        {{"--region", "13,80,7,61", "-o", "out.png"}, "out.png", {54, 67}},
        {{"-a", "0.1", "-s", "2", "--region", "13,80,7,61", "-o", "out.ppm"},
         "out.ppm",
         {54, 67, 56, 69}},
        {{"-m", "normal", "--no-shadows", "-o", "out.ppm"}, "out.ppm", {}},
    };
    const char* const threads[] = {"1", "3", "2"};
    int trial = 0;
    for (const Case& c : cases) {
        const std::string expected = uninterrupted(dir, with(c.args, {"-j", "2"}), c.output);
        for (const double share : {0.15, 0.6}) {
            stop_part_way(dir, with(c.args, {"-j", "2"}), share, SIGKILL, c.rows);
            CHECK(!fs::exists(dir / c.output));
            const RunResult r = resume(dir, with(c.args, {"-j", threads[trial++ % 3]}));
            CHECK_EQ(r.status, 0);
            CHECK_CONTAINS(r.err, "rt: resuming from 'c.ck': ");
            CHECK(read_file(dir / c.output) == expected);
            CHECK(!fs::exists(dir / "c.ck"));  // removed once the image is written
            fs::remove(dir / c.output);
        }
    }
}

TEST(sigterm_leaves_a_complete_checkpoint_and_rt_ends_as_killed_by_it) {
    const fs::path dir = resume_dir("resume_sigterm");
    const std::string expected = uninterrupted(dir, {"-o", "out.png"}, "out.png");
    for (const int sig : {SIGTERM, SIGINT, SIGHUP}) {
        stop_part_way(dir, {"-o", "out.png", "-j", "2"}, 0.4, sig);
        CHECK_CONTAINS(read_file(dir / "rt.err"), "rt: interrupted");
        // The handler waits for a record being written and lets no other begin.
        CHECK(!checkpoint_in(dir / "c.ck").damaged);
        const RunResult r = resume(dir, {"-o", "out.png"});
        CHECK_EQ(r.status, 0);
        CHECK(read_file(dir / "out.png") == expected);
        fs::remove(dir / "out.png");
    }
}

TEST(a_render_interrupted_twice_still_comes_out_the_same) {
    const fs::path dir = resume_dir("resume_twice");
    const std::vector<std::string> args{"-a", "0.05", "-o", "out.ppm"};
    const std::string expected = uninterrupted(dir, args, "out.ppm");
    const Rows rows{72, 96, 72, 96};
    stop_part_way(dir, args, 0.3, SIGKILL, rows);
    const std::size_t first = checkpoint_in(dir / "c.ck").rows.size();
    const int status =
        stop_at_size(dir, with({"scene.in", "--checkpoint", "c.ck", "--resume"}, args),
                     dir / "c.ck", bytes_at(0.9, rows));
    CHECK(WIFSIGNALED(status));
    CHECK(checkpoint_in(dir / "c.ck").rows.size() > first);
    const RunResult r = resume(dir, with(args, {"--stats"}));
    CHECK_EQ(r.status, 0);
    CHECK(read_file(dir / "out.ppm") == expected);
    // -a's two passes: the one-ray rows and the final ones, 72 each.
    CHECK_CONTAINS(r.err, " of 144 rows resumed, ");
}

TEST(options_that_leave_the_raster_alone_may_change_on_resume) {
    const fs::path dir = resume_dir("resume_other_output");
    const std::vector<std::string> later{"-o",       "out.png", "--bits", "16",
                                         "--no-bvh", "-j",      "1",      "--no-metadata"};
    const std::string expected = uninterrupted(dir, later, "out.png");
    stop_part_way(dir, {"-o", "first.ppm", "-j", "2"}, 0.5);
    const RunResult r = resume(dir, later);
    CHECK_EQ(r.status, 0);
    CHECK(read_file(dir / "out.png") == expected);
}

TEST(a_checkpoint_of_another_render_is_refused_with_what_differs_and_left_alone) {
    const fs::path dir = resume_dir("resume_mismatch");
    write_file(dir / "out.png", "precious");
    stop_part_way(dir, {"-o", "out.png"}, 0.5);
    CHECK_EQ(read_file(dir / "out.png"), std::string("precious"));
    const std::string kept = read_file(dir / "c.ck");
    const auto refused = [&](const std::vector<std::string>& args, const std::string& says) {
        const RunResult r = resume(dir, with({"-o", "out.png"}, args));
        CHECK_EQ(r.status, 1);
        CHECK_CONTAINS(r.err, "c.ck: the checkpoint was made by another render (");
        CHECK_CONTAINS(r.err, says);
        CHECK(read_file(dir / "c.ck") == kept);
        CHECK_EQ(read_file(dir / "out.png"), std::string("precious"));
    };
    refused({"-d", "3"}, "depth: 3 here, 7 in the checkpoint");
    refused({"-w", "0.5"}, "weight: 0.5 here, 0.01 in the checkpoint");
    refused({"--size", "48x36"}, "size: 48x36 here, 96x72 in the checkpoint");
    refused({"--region", "0,96,0,36"}, "region: 0,96,0,36 here, 0,96,0,72 in the checkpoint");
    refused({"-s", "2"}, "samples: 2 here, 1 in the checkpoint");
    refused({"-a", "0.1"}, "adaptive: 0.1 here, off in the checkpoint");
    refused({"-m", "depth"}, "mode: depth here, trace in the checkpoint");
    refused({"--no-shadows", "--no-ambient"},
            "switches: --no-ambient --no-shadows here, none in the checkpoint");
    // Another scene: one more comment is other bytes.
    write_file(dir / "scene.in", std::string(kResumeScene) + "# changed\n");
    refused({}, "scene: sha256 ");
    write_file(dir / "scene.in", kResumeScene);
    // Another texture, of the same name.
    const std::string texture = read_file(dir / "letter-f.ppm");
    std::string changed = texture;
    changed[changed.size() - 1] = static_cast<char>(changed.back() ^ 1);
    write_file(dir / "letter-f.ppm", changed);
    refused({}, "input 1: texture 'letter-f.ppm' sha256 ");
    write_file(dir / "letter-f.ppm", texture);
    // Another version of rt: the same rows under a header that names another.
    rt::CheckpointContents old = checkpoint_in(dir / "c.ck");
    for (auto& [key, value] : old.header)
        if (key == "version") value = "rt 0.0.1";
    std::string bytes = rt::encode_checkpoint_start(old.header);
    for (const rt::CheckpointRow& row : old.rows) bytes += rt::encode_checkpoint_row(row);
    write_file(dir / "c.ck", bytes);
    const RunResult r = resume(dir, {"-o", "out.png"});
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "here, rt 0.0.1 in the checkpoint");
    CHECK(read_file(dir / "c.ck") == bytes);
    // And the right command still resumes it.
    write_file(dir / "c.ck", kept);
    CHECK_EQ(resume(dir, {"-o", "out.png"}).status, 0);
    CHECK(read_file(dir / "out.png") != "precious");
}

TEST(the_checkpoints_file_is_checked_before_anything_is_rendered) {
    const fs::path dir = resume_dir("resume_refusals");
    // --resume without a checkpoint: a render from the start, and a word about it.
    const std::string expected = uninterrupted(dir, {"-o", "out.ppm"}, "out.ppm");
    RunResult r = resume(dir, {"-o", "out.ppm"});
    CHECK_EQ(r.status, 0);
    CHECK_CONTAINS(r.err,
                   "rt: note: no checkpoint 'c.ck' to resume from: rendering from the start");
    CHECK(read_file(dir / "out.ppm") == expected);
    CHECK(!fs::exists(dir / "c.ck"));
    // A checkpoint there, without --resume: its work is not thrown away.
    stop_part_way(dir, {"-o", "out.ppm"}, 0.3);
    const std::string kept = read_file(dir / "c.ck");
    r = run_rt_args(dir, {"scene.in", "--checkpoint", "c.ck", "-o", "out.ppm"});
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "c.ck: is already there: add --resume to continue from it");
    CHECK(read_file(dir / "c.ck") == kept);
    // A file that is no checkpoint is never written over.
    write_file(dir / "notes.txt", "my notes\n");
    r = run_rt_args(dir, {"scene.in", "--checkpoint", "notes.txt", "--resume", "-o", "out.ppm"});
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "notes.txt: it is not an rt checkpoint");
    CHECK_EQ(read_file(dir / "notes.txt"), std::string("my notes\n"));
    // Nor a file the render reads or writes, nor anything but a regular file.
    r = run_rt_args(dir, {"scene.in", "--checkpoint", "letter-f.ppm", "--resume", "-o", "x.ppm"});
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "letter-f.ppm: is the texture 'letter-f.ppm', which this render reads");
    fs::create_symlink("out.ppm", dir / "link.ck");
    r = run_rt_args(dir, {"scene.in", "--checkpoint", "link.ck", "-o", "out.ppm"});
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "link.ck: is also an output of this render ('out.ppm')");
    fs::create_directory(dir / "ck-dir");
    r = run_rt_args(dir, {"scene.in", "--checkpoint", "ck-dir", "-o", "x.ppm"});
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "ck-dir: a checkpoint must be a regular file");
    CHECK(!fs::exists(dir / "x.ppm"));
    // What the command line alone can tell.
    const std::pair<std::vector<std::string>, std::string> usage[] = {
        {{"scene.in", "--resume", "-o", "x.ppm"}, "--resume continues from a checkpoint"},
        {{"scene.in", "--checkpoint", "x.ppm", "-o", "x.ppm"},
         "--checkpoint and -o name the same file"},
        {{"scene.in", "--checkpoint", "-", "-o", "x.ppm"}, "--checkpoint needs a file name"},
        {{"scene.in", "--checkpoint", "scene.in", "-o", "x.ppm"},
         "--checkpoint and the scene name the same file"},
    };
    for (const auto& [args, says] : usage) {
        r = run_rt_args(dir, args);
        CHECK_EQ(r.status, 2);
        CHECK_CONTAINS(r.err, says);
    }
}

TEST(a_scene_from_standard_input_is_identified_by_its_bytes) {
    const fs::path dir = resume_dir("resume_stdin");
    // The image records its scene's name, and this one has none.
    const std::string expected = uninterrupted(dir, {"-o", "out.ppm", "--no-metadata"}, "out.ppm");
    const auto with_stdin = [&](const std::string& scene, const std::vector<std::string>& args,
                                bool slow_kill) {
        write_file(dir / "piped.in", scene);
        const int in = ::open((dir / "piped.in").c_str(), O_RDONLY);
        SpawnOptions options;
        options.stdin_fd = in;
        int status = 0;
        if (slow_kill) {
            options.env = {"RT_DEBUG=checkpoint-slow"};
            const pid_t pid = spawn_rt(dir, args, options);
            while (size_of(dir / "c.ck") < bytes_at(0.4) && ::waitpid(pid, &status, WNOHANG) == 0)
                std::this_thread::sleep_for(std::chrono::microseconds(300));
            ::kill(pid, SIGKILL);
            status = wait_for(pid);
        } else {
            status = wait_for(spawn_rt(dir, args, options));
        }
        ::close(in);
        return status;
    };
    const std::vector<std::string> args{"--checkpoint", "c.ck", "-o", "out.ppm", "--no-metadata"};
    CHECK(WIFSIGNALED(with_stdin(kResumeScene, args, true)));
    const std::vector<std::string> again = with(args, {"--resume"});
    int status =
        with_stdin(std::string(kResumeScene) + "1 0.1  0 3 0\n100 1 1 1 0 1 1 0 1\n", again, false);
    CHECK_EQ(WEXITSTATUS(status), 1);
    CHECK_CONTAINS(read_file(dir / "rt.err"), "scene: sha256 ");
    status = with_stdin(kResumeScene, again, false);
    CHECK_EQ(WEXITSTATUS(status), 0);
    CHECK(read_file(dir / "out.ppm") == expected);
}

TEST(a_damaged_checkpoint_loses_only_its_damaged_part) {
    const fs::path dir = resume_dir("resume_damaged");
    const std::string expected = uninterrupted(dir, {"-o", "out.ppm"}, "out.ppm");
    stop_part_way(dir, {"-o", "out.ppm"}, 0.6);
    const std::string kept = read_file(dir / "c.ck");
    const std::size_t rows = checkpoint_in(dir / "c.ck").rows.size();
    // Cut inside the fourth row's record: three rows stay.
    const std::size_t start =
        static_cast<std::size_t>(checkpoint_in(dir / "c.ck").kept_bytes) - rows * 2330;
    write_file(dir / "c.ck", kept.substr(0, start + 3 * 2330 + 1000));
    RunResult r = resume(dir, {"-o", "out.ppm", "--stats"});
    CHECK_EQ(r.status, 0);
    CHECK_CONTAINS(r.err, "c.ck: cut off a damaged or incomplete tail of 1000 bytes");
    CHECK_CONTAINS(r.err, "rt: resuming from 'c.ck': 3 of 72 rows done");
    CHECK_CONTAINS(r.err, "checkpoint: 3 of 72 rows resumed, 69 rendered");
    CHECK(read_file(dir / "out.ppm") == expected);
    // A damaged header: nothing in the file can be trusted, and the render starts again.
    std::string bad = kept;
    bad[30] = static_cast<char>(bad[30] ^ 0x20);
    write_file(dir / "c.ck", bad);
    r = resume(dir, {"-o", "out.ppm"});
    CHECK_EQ(r.status, 0);
    CHECK_CONTAINS(r.err,
                   "c.ck: its header is incomplete or damaged, so nothing in it can be "
                   "used: rendering from the start");
    CHECK(read_file(dir / "out.ppm") == expected);
}

TEST(a_full_disk_costs_the_checkpoint_not_the_render) {
    const fs::path dir = resume_dir("resume_full_disk");
    const std::string expected = uninterrupted(dir, {"-o", "out.png"}, "out.png");
    // Files may grow to 40 blocks of 512 bytes: the image fits, the checkpoint does not. The
    // shell ignores SIGXFSZ, so a write beyond the limit fails (EFBIG) as on a full disk.
    const RunResult r = run_program("sh", dir,
                                    "-c \"trap '' XFSZ; ulimit -f 40; exec '" + rt_binary() +
                                        "' scene.in --checkpoint c.ck -o out.png\"");
    CHECK_EQ(r.status, 0);
    CHECK_CONTAINS(r.err,
                   "rt: warning: c.ck: cannot write the checkpoint (File too large): the "
                   "render goes on without checkpoints");
    CHECK(read_file(dir / "out.png") == expected);
    CHECK(!fs::exists(dir / "c.ck"));
}
