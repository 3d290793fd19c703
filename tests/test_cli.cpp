// The command line as users call it: options, exit statuses, stdin and stdout, and that a
// failed run never touches an existing output file.
#include "batch/cli.h"
#include "check.h"
#include "cli_util.h"
#include "common/message_text.h"
#include "common/option_reader.h"
#include "error_cases.h"
#include "process_util.h"

using namespace rt_test;
namespace fs = std::filesystem;

namespace {

const std::string kScene = kSmallScene;

constexpr const char* kKeep = "previous image, must survive";

}  // namespace

TEST(renders_a_file_to_a_ppm) {
    const fs::path dir = work_dir("render");
    write_file(dir / "scene.in", kScene);
    const RunResult r = run_rt(dir, "-d 7 --no-metadata scene.in -o out.ppm");
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.err, std::string());
    const std::string image = read_file(dir / "out.ppm");
    CHECK_EQ(image.substr(0, 11), std::string("P6\n8 6\n255\n"));
    CHECK_EQ(image.size(), 11u + 8 * 6 * 3);
    // No temporary file is left behind.
    int files = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
    CHECK_EQ(files, 5);  // scene.in, out.ppm, rt.out, rt.err, rt.status
}

TEST(stdin_and_stdout) {
    const fs::path dir = work_dir("pipes");
    write_file(dir / "scene.in", kScene);
    // The scene's name is in the image's metadata; without it, the same bytes.
    CHECK_EQ(run_rt(dir, "--no-metadata scene.in -o file.ppm").status, 0);
    const std::string from_file = read_file(dir / "file.ppm");
    RunResult r = run_rt(dir, "--no-metadata < scene.in");  // no scene: stdin; no -o: stdout
    CHECK_EQ(r.status, 0);
    CHECK(r.out == from_file);
    r = run_rt(dir, "--no-metadata - -o - < scene.in");
    CHECK(r.out == from_file);
    CHECK(run_rt(dir, "-j 1 scene.in").out == run_rt(dir, "-j 3 scene.in").out);
}

TEST(a_scene_name_with_a_line_break_is_recorded_escaped) {
    // A PPM comment cannot hold a line break, and rt's own record of the name must not make
    // the image unwritable: it is recorded as messages show it.
    const fs::path dir = work_dir("name_with_newline");
    write_file(dir / "a\nb.in", kScene);
    for (const std::string out : {"out.ppm", "out.png"}) {
        const RunResult r = run_rt_args(dir, {"a\nb.in", "-o", out});
        CHECK_EQ(r.status, 0);
        CHECK_CONTAINS(read_file(dir / out), "a\\x0ab.in");
    }
}

TEST(read_only_prints_a_summary_and_renders_nothing) {
    const fs::path dir = work_dir("read_only");
    write_file(dir / "scene.in", kScene);
    const RunResult r = run_rt(dir, "-r scene.in -o out.ppm");
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.out, std::string("scene.in: 1 objects, 1 lights, 8x6\n"));
    CHECK(!fs::exists(dir / "out.ppm"));
    CHECK_EQ(run_rt(dir, "-r < scene.in").out, std::string("<stdin>: 1 objects, 1 lights, 8x6\n"));
}

// An empty scene from a pipe says so (the program meant to write it has failed, and said why);
// the readable language given to rt is pointed to rtpp.
TEST(an_empty_pipe_and_a_readable_scene_get_messages_that_say_what_happened) {
    const fs::path dir = work_dir("empty_input");
    write_file(dir / "empty.in", "");
    RunResult r = run_rt(dir, "-o out.ppm < empty.in");
    CHECK_EQ(r.status, 1);
    CHECK_EQ(r.err, std::string("<stdin>:1:1: the scene is empty: nothing came on standard "
                                "input (when a program writes it, as in 'rtpp scene.rts | rt', "
                                "see that program's error above)\n"));
    write_file(dir / "first.rts", "# a camera\ncamera { position <0, 0, 5> look_at <0, 0, 0> }\n");
    r = run_rt(dir, "first.rts -o out.ppm");
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "first.rts:2:1: expected object ID (a number), got 'camera'\n");
    CHECK_CONTAINS(r.err,
                   "first.rts:2:1: note: this looks like rt's readable scene language, "
                   "which rtpp compiles to the numeric format rt reads: rtpp SCENE.rts | "
                   "rt -o IMAGE\n");
    CHECK(!fs::exists(dir / "out.ppm"));
}

TEST(scene_errors_exit_1_and_keep_the_old_image) {
    const fs::path dir = work_dir("errors");
    const std::string bad[] = {
        "102 0 0 5 0 0 0 1 0 0 0 1 0 8 6\n1 -1 0 0 0 100 1 1 1 0 1 1 0 1\n",
        "102 0 0 5 0 0 0 1 0 0 0 1 0 8 6\n77\n",
        "102 0 0 5 0 0 0 1 0 0 0 1 0 8 6\n1 1 0 0\n",
        "1 1 0 0 0 100 1 1 1 0 1 1 0 1\n",
        "102 0 0 5 0 0 0 1 0 0 0 1 0 100000 100000\n",
    };
    const std::string where[] = {"bad.in:2:3: sphere radius must be > 0, got -1",
                                 "bad.in:2:1: unknown object ID 77",
                                 "bad.in:2:8: unexpected end of file: expected sphere centre",
                                 "bad.in:1:30: no viewer (102) in the scene",
                                 "bad.in:1:29: viewer x resolution must be between 1 and 16384"};
    for (std::size_t i = 0; i < std::size(bad); ++i) {
        write_file(dir / "bad.in", bad[i]);
        write_file(dir / "out.ppm", kKeep);
        const RunResult r = run_rt(dir, "bad.in -o out.ppm");
        CHECK_EQ(r.status, 1);
        CHECK_CONTAINS(r.err, where[i]);
        CHECK_EQ(read_file(dir / "out.ppm"), std::string(kKeep));
        CHECK_EQ(r.out, std::string());
    }
    write_file(dir / "bad.in", bad[0]);
    CHECK_CONTAINS(run_rt(dir, "- < bad.in").err, "<stdin>:2:3: sphere radius must be > 0");
}

TEST(every_scene_error_exits_1_with_its_place_and_keeps_the_old_image) {
    const fs::path dir = work_dir("all_errors");
    for (const ErrorCase& c : scene_error_cases()) {
        write_file(dir / "test.in", c.scene);
        write_file(dir / "out.ppm", kKeep);
        const RunResult r = run_rt(dir, "test.in -o out.ppm");
        CHECK_EQ(r.status, 1);
        CHECK_CONTAINS(r.err, c.message);
        CHECK_EQ(read_file(dir / "out.ppm"), std::string(kKeep));
    }
}

TEST(io_errors_exit_1) {
    const fs::path dir = work_dir("io");
    write_file(dir / "scene.in", kScene);
    RunResult r = run_rt(dir, "missing.in -o out.ppm");
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "missing.in: cannot open scene file: No such file or directory");
    CHECK(!fs::exists(dir / "out.ppm"));
    r = run_rt(dir, "scene.in -o no/such/dir/out.ppm");
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "no/such/dir/out.ppm: cannot write the image");
    fs::create_directory(dir / "adir");
    r = run_rt(dir, "scene.in -o adir");
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "adir: cannot write the image: it is a directory");
    r = run_rt(dir, "adir");
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "adir: is a directory");
}

TEST(usage_errors_exit_2) {
    const fs::path dir = work_dir("usage");
    write_file(dir / "scene.in", kScene);
    const std::string bad[] = {"-x scene.in",     "-d",
                               "-d abc scene.in", "-d -1 scene.in",
                               "-w x scene.in",   "-m fancy scene.in",
                               "a.in b.in",       "--no-shadows=1 scene.in",
                               "-s 0 scene.in",   "-j 0 scene.in",
                               "-a -1 scene.in",  "-a x scene.in",
                               "-a inf scene.in", "-a nan scene.in",
                               "scene.in -a",     "--adaptive=0.1x scene.in"};
    for (const std::string& args : bad) {
        write_file(dir / "out.ppm", kKeep);
        const RunResult r = run_rt(dir, args + " -o out.ppm");
        CHECK_EQ(r.status, 2);
        CHECK_CONTAINS(r.err, "rt: ");
        CHECK_CONTAINS(r.err, "Try 'rt --help'");
        CHECK_EQ(read_file(dir / "out.ppm"), std::string(kKeep));
    }
}

TEST(help_and_version) {
    const fs::path dir = work_dir("help");
    RunResult r = run_rt(dir, "--help");
    CHECK_EQ(r.status, 0);
    CHECK_CONTAINS(r.out, "usage: rt [options] [--] [scene]");
    CHECK_CONTAINS(r.out, "-M, --depend FILE");
    CHECK_CONTAINS(r.out, "--no-refraction");
    CHECK_CONTAINS(r.out, "-a, --adaptive T");
    r = run_rt(dir, "--version");
    CHECK_EQ(r.status, 0);
    CHECK_CONTAINS(r.out, "rt " RT_VERSION);
}

TEST(parse_command_line_values) {
    const rt::CommandLine cl =
        rt::parse_command_line({"-d", "3", "-w0.5", "--mode=color", "-o", "x.ppm", "--no-shadows",
                                "--no-ambient", "--threads", "4", "-s", "2", "in.scene"});
    CHECK_EQ(cl.render.max_depth, 3);
    CHECK_EQ(cl.render.min_weight, 0.5);
    CHECK(cl.render.mode == rt::RenderMode::colour);
    CHECK_EQ(cl.output, std::string("x.ppm"));
    CHECK_EQ(cl.input, std::string("in.scene"));
    CHECK(!cl.render.shadows && !cl.render.ambient && cl.render.diffuse);
    CHECK_EQ(cl.render.threads, 4);
    CHECK_EQ(cl.render.samples, 2);
    const rt::CommandLine defaults = rt::parse_command_line({});
    CHECK_EQ(defaults.render.max_depth, 7);
    CHECK_EQ(defaults.render.min_weight, 0.01);
    CHECK_EQ(defaults.input, std::string("-"));
    CHECK_EQ(defaults.output, std::string("-"));
    CHECK(rt::parse_command_line({"-m", "trace"}).render.mode == rt::RenderMode::trace);
    CHECK(rt::parse_command_line({"-m", "depth"}).render.mode == rt::RenderMode::depth);
    CHECK(rt::parse_command_line({"-m", "colour"}).render.mode == rt::RenderMode::colour);
    CHECK(rt::parse_command_line({"-mnormal"}).render.mode == rt::RenderMode::normal);
}

TEST(no_bvh_renders_the_same_bytes) {
    const fs::path dir = work_dir("no-bvh");
    write_file(dir / "scene.in", kScene + "2 -1 0 1 0 100 .5 .5 .5 .5 10 .8 0 1\n");
    CHECK_EQ(run_rt(dir, "scene.in -o fast.ppm").status, 0);
    CHECK_EQ(run_rt(dir, "--no-bvh scene.in -o slow.ppm").status, 0);
    CHECK(read_file(dir / "fast.ppm") == read_file(dir / "slow.ppm"));
    CHECK(rt::parse_command_line({}).render.accelerate);
    CHECK(!rt::parse_command_line({"--no-bvh"}).render.accelerate);
    CHECK_EQ(run_rt(dir, "--no-bvh=1 scene.in").status, 2);
}

TEST(adaptive_option) {
    CHECK(!rt::parse_command_line({}).render.adaptive_threshold);
    rt::CommandLine cl = rt::parse_command_line({"-a", "0.1"});
    CHECK(cl.render.adaptive_threshold == 0.1);
    CHECK_EQ(cl.render.samples, 3);  // the grid -a uses when -s is not given
    cl = rt::parse_command_line({"-s", "5", "--adaptive=0"});
    CHECK(cl.render.adaptive_threshold == 0.0);
    CHECK_EQ(cl.render.samples, 5);
    cl = rt::parse_command_line({"-a0.25", "-s2"});  // -s after -a counts too
    CHECK(cl.render.adaptive_threshold == 0.25);
    CHECK_EQ(cl.render.samples, 2);
    CHECK_EQ(rt::parse_command_line({"-s", "2"}).render.samples, 2);

    const fs::path dir = work_dir("adaptive");
    write_file(dir / "scene.in", kScene);
    RunResult r = run_rt(dir, "-a -1 scene.in");
    CHECK_CONTAINS(r.err, "rt: -a expects a number >= 0, got '-1'");
    // A threshold no difference exceeds renders the one-ray image; any threshold renders the
    // same bytes on any number of threads.
    CHECK_EQ(run_rt(dir, "--no-metadata scene.in -o one.ppm").status, 0);
    CHECK_EQ(run_rt(dir, "--no-metadata -a 1 scene.in -o above.ppm").status, 0);
    CHECK(read_file(dir / "one.ppm") == read_file(dir / "above.ppm"));
    CHECK_EQ(run_rt(dir, "-a 0.05 -j 1 scene.in -o j1.ppm").status, 0);
    CHECK_EQ(run_rt(dir, "-a 0.05 -j 3 scene.in -o j3.ppm").status, 0);
    CHECK(read_file(dir / "j1.ppm") == read_file(dir / "j3.ppm"));
    CHECK(read_file(dir / "j1.ppm") != read_file(dir / "one.ppm"));
}

TEST(conventions) {
    const fs::path dir = work_dir("conventions");
    write_file(dir / "-x.in", kScene);
    // "--" ends the options: a scene whose name starts with '-'.
    RunResult r = run_rt(dir, "-r -- -x.in");
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.out, std::string("-x.in: 1 objects, 1 lights, 8x6\n"));
    CHECK_EQ(run_rt(dir, "-r -x.in").status, 2);
    CHECK_EQ(run_rt(dir, "-r -- -x.in extra").status, 2);
    // A leading '+' on numbers.
    const rt::CommandLine cl =
        rt::parse_command_line({"-d", "+5", "-j+2", "--samples=+3", "-w", "+0.5", "-a", "+.1"});
    CHECK_EQ(cl.render.max_depth, 5);
    CHECK_EQ(cl.render.threads, 2);
    CHECK_EQ(cl.render.samples, 3);
    CHECK_EQ(cl.render.min_weight, 0.5);
    CHECK(cl.render.adaptive_threshold == 0.1);
    // Range errors say so, whatever the size of the number.
    for (const char* args : {"-d 65", "-d -1", "-j 99999999999999999999", "-s 65", "-s 0"}) {
        r = run_rt(dir, std::string(args) + " -r -- -x.in");
        CHECK_EQ(r.status, 2);
        CHECK_CONTAINS(r.err, "is out of range");
    }
    CHECK_CONTAINS(run_rt(dir, "-d 65").err, "rt: -d 65 is out of range (0 to 64)");
    CHECK_CONTAINS(run_rt(dir, "-d 99999999999999999999").err,
                   "rt: -d 99999999999999999999 is out of range (0 to 64)");
    CHECK_CONTAINS(run_rt(dir, "-w 1e-400").err,
                   "rt: -w 1e-400 is too small to tell from 0 (below about 4.9e-324); write 0");
    CHECK_CONTAINS(run_rt(dir, "-w 1e400").err,
                   "rt: -w 1e400 is out of range (above about 1.8e308)");
    CHECK_CONTAINS(run_rt(dir, "-d +x").err, "-d expects a whole number, got '+x'");
    CHECK_CONTAINS(run_rt(dir, "-d ++5").err, "-d expects a whole number, got '++5'");
}

// getopt's conventions: short options bundle, the last of a bundle may take the rest as its
// value; a misspelt option is answered with the nearest, in all three programs.
TEST(short_options_bundle_and_misspelt_ones_get_a_suggestion) {
    const fs::path dir = work_dir("bundles");
    write_file(dir / "scene.in", kScene);
    RunResult r = run_rt(dir, "-qr scene.in");
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.out, std::string("scene.in: 1 objects, 1 lights, 8x6\n"));
    const rt::CommandLine cl = rt::parse_command_line({"-qoout.png", "-d3", "scene.in"});
    CHECK(cl.quiet);
    CHECK_EQ(cl.output, std::string("out.png"));
    CHECK_EQ(cl.render.max_depth, 3);
    const rt::CommandLine split = rt::parse_command_line({"-qo", "out.png", "scene.in"});
    CHECK_EQ(split.output, std::string("out.png"));
    r = run_rt(dir, "-qx scene.in");
    CHECK_EQ(r.status, 2);
    CHECK_CONTAINS(r.err, "rt: unknown option '-x' (in '-qx')");
    for (const auto& [typed, meant] :
         {std::pair{"--no-shadow", "--no-shadows"}, std::pair{"--stat", "--stats"},
          std::pair{"--sampels", "--samples"}, std::pair{"--regoin", "--region"}}) {
        r = run_rt(dir, std::string(typed) + " scene.in");
        CHECK_EQ(r.status, 2);
        CHECK_CONTAINS(r.err, join("unknown option '", typed, "'; did you mean '", meant, "'?"));
    }
    // Nothing near enough: no suggestion.
    r = run_rt(dir, "--frobnicate scene.in");
    CHECK_EQ(r.err, std::string("rt: unknown option '--frobnicate'\nTry 'rt --help' for more "
                                "information.\n"));
    CHECK_CONTAINS(run_program(RTPP_BINARY, dir, "--incude x").err,
                   "rtpp: unknown option '--incude'; did you mean '--include'?");
    CHECK_CONTAINS(run_program(RTIMG_BINARY, dir, "diff --tolerence 2 a b").err,
                   "rtimg: unknown option '--tolerence'; did you mean '--tolerance'?");
    CHECK_EQ(rt::nearest_word("--bits", {"--bits", "--gamma"}), std::string("--bits"));
    CHECK_EQ(rt::nearest_word("-x", {"-q", "-r"}), std::string());
}

// "rt scene.in > out.png" writes PPM (rt cannot see the name behind a redirect when it
// chooses), and says so, since it can learn the name afterwards; -f or a PPM name is quiet.
TEST(a_redirect_to_a_name_of_another_format_is_warned_about) {
    const fs::path dir = work_dir("redirect_format");
    write_file(dir / "scene.in", kScene);
    // Run through the shell with its own redirect (run_rt redirects standard output itself).
    const auto redirected = [&](const std::string& args, const std::string& to) {
        CHECK_EQ(shell(join("cd '", dir.string(), "' && '", rt_binary(), "' ", args, " >", to,
                            " 2>err.txt")),
                 0);
        return read_file(dir / "err.txt");
    };
    const std::string err = redirected("scene.in", "out.png");
    CHECK_CONTAINS(err, "rt: warning: standard output is '" + (dir / "out.png").string() +
                            "', but rt writes PPM there: a redirect hides the name rt chooses "
                            "the format by (use -o out.png, or -f png)\n");
    CHECK_EQ(read_file(dir / "out.png").substr(0, 2), std::string("P6"));
    CHECK_EQ(redirected("-f png scene.in", "out.png"), "");
    CHECK_EQ(read_file(dir / "out.png").substr(1, 3), std::string("PNG"));
    CHECK_EQ(redirected("scene.in", "out.ppm"), "");
    CHECK_EQ(redirected("-q scene.in", "out.png"), "");
}

TEST(text_that_cannot_be_written_is_an_error) {
    // /dev/full takes no data (ENOSPC). It is only a redirection here, never an -o target.
    if (!fs::exists("/dev/full")) return;
    const fs::path dir = work_dir("full");
    write_file(dir / "scene.in", kScene);
    const int full = ::open("/dev/full", O_WRONLY);
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"--help"}, {"--version"}, {"-r", "scene.in"}}) {
        const RunResult r = run_rt_args(dir, args, stdout_to(full));
        CHECK_EQ(r.status, 1);
        CHECK_CONTAINS(r.err, "rt: cannot write to standard output: No space left on device");
    }
    const RunResult r = run_rt_args(dir, {"scene.in"}, stdout_to(full));
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "<stdout>: cannot write the image: No space left on device");
    ::close(full);
    // rtpp and rtimg check their text the same way (common/exit_status.h).
    for (const std::string program : {RTPP_BINARY, RTIMG_BINARY}) {
        const std::string name = fs::path(program).filename().string();
        for (const char* option : {"--help", "--version"}) {
            CHECK_EQ(shell("cd '" + dir.string() + "' && '" + program + "' " + option +
                           " >/dev/full 2>text.err; echo $? >text.status"),
                     0);
            CHECK_EQ(read_file(dir / "text.status"), std::string("1\n"));
            CHECK_EQ(read_file(dir / "text.err"),
                     name + ": cannot write to standard output: No space left on device\n");
        }
    }
}

// One rule for the numbers rt and rtimg take (common/option_reader.h): a leading '+' before a
// digit or '.', decimal only.
TEST(numbers_follow_one_rule_in_rt_and_rtimg) {
    CHECK_EQ(rt::parse_nonnegative("-w", "+0.5"), 0.5);
    CHECK_EQ(rt::parse_nonnegative("-w", "+.25"), 0.25);
    CHECK_EQ(rt::parse_whole_number("-d", "+7", 0, 64), 7);
    for (const char* bad : {"+", "++1", "+-1", "-1", "+inf", "inf", "nan", "0x10", "1e", ""}) {
        bool refused = false;
        try {
            rt::parse_nonnegative("-w", bad);
        } catch (const rt::UsageError& e) {
            refused = e.message == "-w expects a number >= 0, got " + rt::quote_token(bad);
        }
        CHECK(refused);
    }
    const fs::path dir = work_dir("plus");
    write_file(dir / "scene.in", kScene);
    CHECK_EQ(run_rt(dir, "scene.in -w +0.01 -o a.ppm").status, 0);
    CHECK_EQ(run_rt(dir, "scene.in -d +7 -o b.ppm").status, 0);
    RunResult r = run_rtimg(dir, "diff --tolerance +2 --max-fraction=+.5 a.ppm b.ppm");
    CHECK_EQ(r.status, 0);
    CHECK_CONTAINS(r.out, "result: pass");
    r = run_rtimg(dir, "diff --tolerance ++2 a.ppm b.ppm");
    CHECK_EQ(r.status, 2);
    CHECK_CONTAINS(r.err, "rtimg: --tolerance expects a number >= 0, got '++2'");
    r = run_rtimg(dir, "diff --max-fraction 1e400 a.ppm b.ppm");
    CHECK_EQ(r.status, 2);
    CHECK_CONTAINS(r.err, "rtimg: --max-fraction 1e400 is out of range (above about 1.8e308)");
}
