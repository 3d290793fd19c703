// docs/examples/animation works as its Makefile says: make -j renders every frame through rt
// and its -M rules, a second make has nothing to do, and a changed texture re-renders every
// frame; a make -j interrupted by Ctrl-C resumes its frames from their checkpoints to the
// same bytes. Skipped where make is not installed.
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include "check.h"
#include "cli_util.h"

namespace fs = std::filesystem;
using namespace rt_test;

namespace {

const char* const kFlags = "--size 32x24 -q";

// Runs make in the example's copy; returns its exit status.
int make(const fs::path& dir, const std::string& arguments, const std::string& flags = kFlags) {
    const int status =
        shell(join("cd '", dir.string(), "' && make ", arguments, " RT='", RT_BINARY, "' RTPP='",
                   RTPP_BINARY, "' RTFLAGS='", flags, "' >>make.log 2>&1"));
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Whether make would render anything: make -n prints the commands it would run. (make -q
// cannot say: it runs '+' lines, and rt does nothing under it, successfully.)
bool out_of_date(const fs::path& dir, const std::string& flags = kFlags) {
    const fs::path log = dir / "plan.log";
    shell(join("cd '", dir.string(), "' && make -n N=4 RT='", RT_BINARY, "' RTPP='", RTPP_BINARY,
               "' RTFLAGS='", flags, "' >'", log.string(), "' 2>&1"));
    return read_file(log).find(" -M frames/") != std::string::npos;
}

}  // namespace

TEST(the_animation_example_renders_and_rerenders_what_changed) {
    if (!on_path("make")) {
        std::cout << "make is not installed: not checked\n";
        return;
    }
    const fs::path dir = work_dir("animation");
    fs::copy(fs::path(RT_SOURCE_DIR) / "docs" / "examples" / "animation", dir,
             fs::copy_options::recursive);
    CHECK_EQ(make(dir, "-j2 N=4"), 0);
    for (int i = 0; i < 4; ++i) {
        const fs::path frame = dir / "frames" / join("frame-00", i, ".ppm");
        CHECK(fs::exists(frame));
        CHECK_CONTAINS(read_file(frame).substr(0, 2), "P6");
        CHECK(fs::exists(dir / "frames" / join("frame-00", i, ".d")));
    }
    // Each frame's scene is ball.rts with its own number: the ball moves between frames.
    CHECK(read_file(dir / "frames" / "frame-000.in") != read_file(dir / "frames" / "frame-003.in"));
    CHECK_CONTAINS(read_file(dir / "frames" / "frame-000.in"), "ball.rts");
    // Everything is up to date: make -n would run nothing.
    CHECK(!out_of_date(dir));
    // The texture changes: every frame is out of date (through the rules rt -M wrote), and
    // make renders them again. Times are moved into the past, not the future, so make sees
    // no clock skew: the sources long ago, the frames a minute ago, the texture just after.
    const auto now = fs::file_time_type::clock::now();
    for (const auto& entry : fs::recursive_directory_iterator(dir))
        if (entry.is_regular_file())
            fs::last_write_time(entry.path(), now - std::chrono::minutes(2));
    for (const auto& entry : fs::directory_iterator(dir / "frames"))
        if (entry.is_regular_file() && !entry.is_symlink())
            fs::last_write_time(entry.path(), now - std::chrono::minutes(1));
    CHECK(!out_of_date(dir));
    const auto before = fs::last_write_time(dir / "frames" / "frame-000.ppm");
    fs::last_write_time(dir / "checker.ppm", now - std::chrono::seconds(30));
    CHECK(out_of_date(dir));
    CHECK_EQ(make(dir, "-j2 N=4"), 0);
    CHECK(!out_of_date(dir));
    CHECK(fs::last_write_time(dir / "frames" / "frame-003.ppm") > before);
}

// Other RTFLAGS make every frame out of date (a preview is not left standing by a final
// make), and the same ones again leave them alone.
TEST(changed_rtflags_render_the_frames_again) {
    if (!on_path("make")) {
        std::cout << "make is not installed: not checked\n";
        return;
    }
    const fs::path dir = work_dir("animation_flags");
    fs::copy(fs::path(RT_SOURCE_DIR) / "docs" / "examples" / "animation", dir,
             fs::copy_options::recursive);
    CHECK_EQ(make(dir, "-j2 N=4", "--size 16x12 -q"), 0);
    CHECK_CONTAINS(read_file(dir / "frames" / "frame-002.ppm"), "\n16 12\n");
    CHECK(!out_of_date(dir, "--size 16x12 -q"));
    CHECK(out_of_date(dir, "--size 32x24 -q"));
    CHECK_EQ(make(dir, "-j2 N=4", "--size 32x24 -q"), 0);
    CHECK_CONTAINS(read_file(dir / "frames" / "frame-002.ppm"), "\n32 24\n");
    CHECK(!out_of_date(dir, "--size 32x24 -q"));
}

// Ctrl-C in the middle of make -j: the frames being rendered keep their checkpoints, and the
// next make resumes them (rt says so) to exactly the frames of an uninterrupted make.
TEST(an_interrupted_make_resumes_its_frames_to_the_same_bytes) {
    if (!on_path("make")) {
        std::cout << "make is not installed: not checked\n";
        return;
    }
    const std::string flags = "--size 160x120 -s 2";
    const fs::path whole = work_dir("animation_whole");
    const fs::path dir = work_dir("animation_resume");
    for (const fs::path& d : {whole, dir})
        fs::copy(fs::path(RT_SOURCE_DIR) / "docs" / "examples" / "animation", d,
                 fs::copy_options::recursive);
    CHECK_EQ(make(whole, "-j2 N=2", flags), 0);
    // make in a process group of its own, as a shell runs a job, its frames written slowly.
    const std::string command =
        join("cd '", dir.string(), "' && RT_DEBUG=checkpoint-slow exec make -j2 N=2 RT='",
             RT_BINARY, "' RTPP='", RTPP_BINARY, "' RTFLAGS='", flags, "' >>make.log 2>&1");
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::setpgid(0, 0);
        ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
        ::_exit(127);
    }
    ::setpgid(pid, pid);
    const fs::path checkpoint = dir / "frames" / "frame-001.ck";
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    std::error_code ec;
    while ((!fs::exists(checkpoint, ec) || fs::file_size(checkpoint, ec) < 40 * 3900) &&
           std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    ::kill(-pid, SIGINT);  // what Ctrl-C sends: the whole job
    int status = 0;
    ::waitpid(pid, &status, 0);
    CHECK(!fs::exists(dir / "frames" / "frame-001.ppm"));
    CHECK(fs::exists(checkpoint));
    fs::copy_file(checkpoint, dir / "stale.ck");
    CHECK_EQ(make(dir, "-j2 N=2", flags), 0);
    CHECK_CONTAINS(read_file(dir / "make.log"), "rt: resuming from 'frames/frame-001.ck'");
    for (const char* frame : {"frames/frame-000.ppm", "frames/frame-001.ppm"})
        CHECK(read_file(dir / frame) == read_file(whole / frame));
    CHECK(!fs::exists(checkpoint));
    // Other RTFLAGS make the frames out of date, and a checkpoint left from before them
    // (older than .rtflags) is removed by the rule rather than refused by rt.
    fs::copy_file(dir / "stale.ck", checkpoint);
    fs::last_write_time(checkpoint, fs::file_time_type::clock::now() - std::chrono::minutes(1));
    CHECK_EQ(make(dir, "-j2 N=2", "--size 160x120"), 0);
    CHECK(read_file(dir / "make.log").find("made by another render") == std::string::npos);
    CHECK(!fs::exists(checkpoint));
}
