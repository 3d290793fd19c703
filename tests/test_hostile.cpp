// Hostile input (issue 11): memory and time in proportion to the scene, no input that blocks,
// and messages that say truly what was found, escaped and cut.
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <streambuf>

#include "batch/cost.h"
#include "check.h"
#include "cli_util.h"
#include "memory_checks.h"
#include "rt/reader.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;
namespace fs = std::filesystem;

namespace {

const std::string kViewer = kTestViewer;
const std::string kSurface = " 100 1 1 1 0 1 1 0 1";

// Peak resident memory in KiB that reading `text` adds (an error or not), measured in a child
// process so that what the test itself has used does not hide it.
long read_peak_kib(const std::string& text) {
    int fds[2];
    if (::pipe(fds) != 0) return -1;
    const pid_t pid = ::fork();
    if (pid == 0) {
        rusage before{};
        ::getrusage(RUSAGE_SELF, &before);
        try {
            parse_scene(text);
        } catch (const Error&) {  // what it cost to find the error counts too
        }
        rusage after{};
        ::getrusage(RUSAGE_SELF, &after);
        const long grown = after.ru_maxrss - before.ru_maxrss;
        [[maybe_unused]] const auto written = ::write(fds[1], &grown, sizeof grown);
        ::_exit(0);
    }
    ::close(fds[1]);
    long grown = -1;
    if (::read(fds[0], &grown, sizeof grown) != sizeof grown) grown = -1;
    ::close(fds[0]);
    int status = 0;
    ::waitpid(pid, &status, 0);
    return grown;
}

std::string sphere_lights(int count, int samples) {
    std::string text = kViewer;
    for (int i = 0; i < count; ++i) text += join("110 ", samples, " 0 0 ", i % 100, " 1 1 1 1\n");
    return text;
}

}  // namespace

TEST(sphere_lights_cost_no_memory_per_sample) {
    // 40,000 lights of 26 samples each: a lattice per light took 25 MB; now each light is a
    // few dozen bytes whatever its samples.
    const long grown = read_peak_kib(sphere_lights(40000, 26));
    CHECK(grown >= 0);
    if (RT_MEASURES_MEMORY) CHECK(grown < 12 * 1024);
}

TEST(light_samples_are_capped_while_reading) {
    // 256 lights of 4096 samples reach the cap exactly; the next one is refused at its place.
    CHECK_EQ(scene_error(sphere_lights(256, 4096)), std::string());
    CHECK_EQ(scene_error(sphere_lights(40000, 4096)),
             std::string("test.in:258:1: too many light samples: with this light the scene's "
                         "lights take 1052672 samples, more than the limit of 1048576 (each is a "
                         "shadow ray for every point lit)"));
    // The old reproducer: refused at light 257, having cost next to nothing.
    const long grown = read_peak_kib(sphere_lights(40000, 4096));
    CHECK(grown >= 0);
    if (RT_MEASURES_MEMORY) CHECK(grown < 4 * 1024);
}

TEST(a_texture_is_loaded_once_whatever_it_is_called) {
    const fs::path dir = work_dir("hostile_textures");
    fs::create_directories(dir / "tex");
    write_file(dir / "tex" / "t.ppm", "P3 2 1 255 1 2 3 4 5 6\n");
    fs::create_symlink("tex/t.ppm", dir / "link.ppm");
    std::string text = kViewer;
    for (const std::string& path :
         {std::string("tex/t.ppm"), std::string("./tex/t.ppm"), std::string("tex/../tex/t.ppm"),
          (dir / "tex" / "t.ppm").string(), std::string("link.ppm")})
        text += "1 1 0 0 0 108 0 0 0 1 0 0 0 1 0 " + path + kSurface + "\n";
    std::istringstream in(text);
    SceneReader reader(in, "test.in", dir);
    reader.read_scene();
    CHECK_EQ(reader.textures_loaded(), 1u);
    // -M names each spelling (the absolute one is the first, resolved): make compares the
    // time of each, and a link can be re-pointed.
    CHECK_EQ(reader.input_files().size(), 4u);
    CHECK_EQ(reader.input_files().front().path.string(), (dir / "tex/t.ppm").string());
    CHECK_EQ(reader.input_files().back().path.string(), (dir / "link.ppm").string());
    CHECK_EQ(std::string(reader.input_files().back().role), "the texture");
}

TEST(a_texture_that_is_not_a_regular_file_is_refused_without_blocking) {
    const fs::path dir = work_dir("hostile_fifo");
    CHECK_EQ(::mkfifo((dir / "fifo.ppm").c_str(), 0600), 0);
    ::alarm(60);  // a texture open that blocks would otherwise hang the test for ever
    const auto error = [&](const std::string& path) {
        std::istringstream in(kViewer + "1 1 0 0 0 108 0 0 0 1 0 0 0 1 0 " + path + kSurface);
        SceneReader reader(in, "test.in", dir);
        try {
            reader.read_scene();
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK_CONTAINS(error("fifo.ppm"),
                   "test.in:2:33: cannot read texture 'fifo.ppm': it is not a regular file (a "
                   "FIFO)");
    CHECK_CONTAINS(error("/dev/null"),
                   "cannot read texture '/dev/null': it is not a regular file (a character "
                   "device)");
    CHECK_CONTAINS(error("/dev/stdin"), "it is not a regular file");
    CHECK_CONTAINS(error("."), "cannot read texture '.': it is a directory");
    ::alarm(0);
}

TEST(control_bytes_in_a_token_are_errors_shown_escaped) {
    CHECK_EQ(scene_error(kViewer + "1 1" + std::string(1, '\0') + "garbage 0 0 0" + kSurface),
             std::string("test.in:2:4: control character \\x00 in token '1\\x00garbage'"));
    CHECK_EQ(scene_error(kViewer + "\x1b[31mred"),
             std::string("test.in:2:1: control character \\x1b in token '\\x1b[31mred'"));
    CHECK_EQ(scene_error(kViewer + "\"a\x07.ppm\""),
             std::string("test.in:2:3: control character \\x07 in token 'a\\x07.ppm'"));
    // Other bytes that are not printable are escaped, valid UTF-8 kept, long tokens cut.
    CHECK_EQ(scene_error(kViewer + "1 \xff\xc3\xa9"),
             std::string("test.in:2:3: expected sphere radius (a number), got '\\xff\xc3\xa9'"));
    CHECK_EQ(scene_error(kViewer + "1 \xc2\x9b"),
             std::string("test.in:2:3: expected sphere radius (a number), got '\\xc2\\x9b'"));
    CHECK_CONTAINS(scene_error(kViewer + "root:x:0:0:root:/root:/bin/bash:with:a:long:tail"),
                   "test.in:2:1: expected object ID (a number), got "
                   "'root:x:0:0:root:/root:/bin/bash:with:a:l...' (48 bytes)\n");
}

TEST(numbers_are_shown_as_written_and_range_errors_named) {
    CHECK_EQ(scene_error(kViewer + "110 4096.0000001 0 0 0 1 1 1 1"),
             std::string("test.in:2:5: sphere light samples must be a whole number, got "
                         "4096.0000001"));
    CHECK_EQ(scene_error(kViewer + "110 4097.0 0 0 0 1 1 1 1"),
             std::string("test.in:2:5: sphere light samples must be between 1 and 4096, got "
                         "4097.0"));
    CHECK_CONTAINS(scene_error(kViewer + "1e10 1 0 0 0" + kSurface),
                   "test.in:2:1: object ID is out of range (no ID is beyond 1e9), got 1e10");
    CHECK_CONTAINS(scene_error(kViewer + "1 -0.00000000001 0 0 0" + kSurface),
                   "test.in:2:3: sphere radius must be > 0, got -0.00000000001");
}

TEST(a_tiny_direction_is_a_direction) {
    const Scene scene = parse_scene(kViewer + "2 0  0 1e-162 0" + kSurface);
    CHECK_EQ(scene.objects.size(), 1u);
    CHECK_EQ(scene_error(kViewer + "113 1e-300 0 0  1 1 1"), std::string());
    // A vector whose length is used as it is says why it cannot be.
    CHECK_CONTAINS(scene_error("102 0 0 5 0 0 0 1e-162 0 0 0 1 0 4 4"),
                   "test.in:1:17: viewer x vector is too short or too long");
}

TEST(end_of_file_is_reported_after_the_last_token) {
    CHECK_EQ(scene_error(kViewer + "1 1 0 0\n\n# trailing comment\n"),
             std::string("test.in:2:8: unexpected end of file: expected sphere centre"));
    CHECK_EQ(scene_error("103 1 1 1\n\n"), std::string("test.in:1:10: no viewer (102) in the "
                                                       "scene; one is required"));
    CHECK_EQ(scene_error("\n\n"),
             std::string("test.in:1:1: the scene is empty: the file holds no objects (and no "
                         "viewer, 102, which every scene needs)"));
}

namespace {
// Endless blanks, then a token: a line longer than 2^31 bytes without holding it in memory.
class BlankLine : public std::streambuf {
  public:
    explicit BlankLine(std::int64_t blanks) : left_(blanks) {}

  protected:
    int_type underflow() override {
        if (left_ <= 0) {
            if (tail_done_) return traits_type::eof();
            tail_done_ = true;
            setg(tail_, tail_, tail_ + 1);
            return traits_type::to_int_type('x');
        }
        const std::int64_t n = std::min<std::int64_t>(left_, sizeof chunk_);
        std::fill(chunk_, chunk_ + n, ' ');
        left_ -= n;
        setg(chunk_, chunk_, chunk_ + n);
        return ' ';
    }

  private:
    std::int64_t left_;
    bool tail_done_ = false;
    char tail_[1] = {'x'};
    char chunk_[1 << 16];
};
}  // namespace

TEST(columns_are_counted_in_64_bits) {
    // Past 2^31 bytes on one line an int column would wrap negative (undefined behaviour).
    BlankLine buffer((std::int64_t{1} << 31) + 5);
    std::istream in(&buffer);
    SceneReader reader(in, "long.in", {});
    try {
        reader.read_scene();
        CHECK(false);
    } catch (const Error& e) {
        CHECK_CONTAINS(e.what(), "long.in:1:2147483654: expected object ID (a number), got 'x'");
    }
}

TEST(extreme_costs_are_warned_about) {
    Scene scene = parse_scene(sphere_lights(256, 4096));
    scene.viewer.xres = scene.viewer.yres = 512;
    RenderOptions options;
    auto warnings = cost_warnings(scene, options);
    CHECK_EQ(warnings.size(), 1u);
    if (!warnings.empty())
        CHECK_CONTAINS(warnings[0], "512x512 pixels x 1 rays x 1048576 light samples");
    scene.viewer.xres = scene.viewer.yres = 64;
    CHECK(cost_warnings(scene, options).empty());
    options.min_weight = 0;
    options.max_depth = 30;
    // Mirrors alone send one ray per hit: no doubling, no warning.
    CHECK(cost_warnings(scene, options).empty());
    CHECK(cost_warnings(parse_scene(kSmallScene), options).empty());
    // Glass, or a surface with both ks and kt, sends two.
    for (const std::string& surface :
         {std::string(" 114 1 1 1 0 1 0 1.5 0 0 0"), std::string(" 100 1 1 1 .5 1 1 .5 1.5"),
          std::string(" 107 1 100 1 1 1 0 1 1 0 1 114 1 1 1 0 1 0 1.5 0 0 0")}) {
        scene = parse_scene(kViewer + "1 1 0 0 0" + surface);
        warnings = cost_warnings(scene, options);
        CHECK_EQ(warnings.size(), 1u);
        if (!warnings.empty()) CHECK_CONTAINS(warnings[0], "-d 30 with -w 0");
        options.refraction = false;
        CHECK(cost_warnings(scene, options).empty());
        options.refraction = true;
    }
    const fs::path dir = work_dir("hostile_cost");
    write_file(dir / "s.in", kSlowScene);
    // One pixel at -d 17: at most 2^18 rays.
    const RunResult r = run_rt(dir, "--size 1x1 -w 0 -d 17 s.in -o out.ppm");
    CHECK_EQ(r.status, 0);
    CHECK_CONTAINS(r.err, "rt: warning: -d 17 with -w 0: each glass surface can double the rays");
    CHECK_EQ(run_rt(dir, "-q --size 1x1 -w 0 -d 17 s.in -o out.ppm").err, std::string());
    write_file(dir / "s.in", kSmallScene);
    CHECK_EQ(run_rt(dir, "--size 1x1 -w 0 -d 17 s.in -o out.ppm").err, std::string());
}

TEST(read_errors_on_the_scene_are_reported_with_their_reason) {
    const fs::path dir = work_dir("hostile_stdin");
    RunResult r = run_rt(dir, "-r < .");
    CHECK_EQ(r.status, 1);
    CHECK_EQ(r.err, std::string("<stdin>: cannot read the scene: Is a directory\n"));
    r = run_rt(dir, "-r <&-");
    CHECK_EQ(r.status, 1);
    CHECK_EQ(r.err, std::string("<stdin>: cannot read the scene from standard input: Bad file "
                                "descriptor\n"));
}

#if RT_MEASURES_MEMORY  // ASan cannot run under ulimit -v
TEST(a_thread_that_cannot_start_gives_a_hint) {
    // Too little address space for 1024 thread stacks: rt says what to do about it.
    const fs::path dir = work_dir("hostile_threads");
    write_file(dir / "s.in", "102 0 0 5 0 0 0 1 0 0 0 1 0 4 1024\n101 2 3 4 1 1 1\n");
    const std::string command = "cd '" + dir.string() + "' && (ulimit -v 400000; '" + rt_binary() +
                                "' -j 1024 s.in -o out.ppm) 2>rt.err; echo $? >rt.status";
    CHECK_EQ(std::system(command.c_str()), 0);
    CHECK_EQ(read_file(dir / "rt.status"), std::string("1\n"));
    CHECK_CONTAINS(read_file(dir / "rt.err"), "): try a smaller -j");
    CHECK(!fs::exists(dir / "out.ppm"));
}
#endif

TEST(command_line_values_are_shown_escaped_and_cut) {
    const fs::path dir = work_dir("hostile_arguments");
    const std::string escape = "\"$(printf '\\033[31mred')\"";
    RunResult r = run_rt(dir, "-m " + escape);
    CHECK_EQ(r.status, 2);
    CHECK_EQ(r.err, std::string("rt: -m expects trace, depth, colour or normal, got "
                                "'\\x1b[31mred'\nTry 'rt --help' for more information.\n"));
    r = run_rt(dir, "-d " + std::string(100, '9'));
    CHECK_EQ(r.status, 2);
    CHECK_CONTAINS(r.err,
                   "rt: -d 9999999999999999999999999999999999999999... (100 bytes) is out "
                   "of range (0 to 64)\n");
    // A file name is shown whole, escaped.
    r = run_rt(dir, "--no-bvh=1 a.in " + escape + "x.in");
    CHECK_EQ(r.status, 2);
    CHECK_CONTAINS(r.err, "rt: --no-bvh takes no value\n");
    r = run_rt(dir, "a.in " + escape + "x.in");
    CHECK_EQ(r.err, std::string("rt: more than one scene file given ('a.in' and "
                                "'\\x1b[31mredx.in')\nTry 'rt --help' for more information.\n"));
    // Whatever builds a message, no program lets a control byte reach the terminal.
    r = run_rt(dir, escape + ".in -o out.ppm");
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "\\x1b[31mred.in");
    CHECK(r.err.find('\x1b') == std::string::npos);
    r = run_program(RTPP_BINARY, dir, "--" + escape);
    CHECK_EQ(r.status, 2);
    CHECK_CONTAINS(r.err, "rtpp: unknown option '--\\x1b[31mred'\n");
    r = run_program(RTPP_BINARY, dir, escape + ".rts");
    CHECK_EQ(r.status, 1);
    CHECK(r.err.find('\x1b') == std::string::npos);
    r = run_rtimg(dir, "info " + escape + ".png");
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "\\x1b[31mred.png");
    CHECK(r.err.find('\x1b') == std::string::npos);
    r = run_rtimg(dir, "info --" + escape);
    CHECK_EQ(r.status, 2);
    CHECK_CONTAINS(r.err, "rtimg: unknown option '--\\x1b[31mred'\n");
}
