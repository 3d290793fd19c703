// rtpp reading NFF from its command line: by the .nff extension, or --from nff for standard
// input and any name; the result rendered by rt, checked pixel by pixel.
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "check.h"
#include "cli_util.h"
#include "memory_checks.h"
#include "rt/image_file.h"

namespace fs = std::filesystem;
using namespace rt_test;

namespace {

// A red sphere (Kd 1, nothing else) of radius 0.5 at the origin, seen head on from z = 5 at
// 9 x 9 pixels, lit by one light behind the eye (intensity 1/sqrt(1) = 1), before a
// background of 0.25 0.5 0.75.
const std::string kNff = R"(v
from 0 0 5
at 0 0 0
up 0 1 0
angle 45
hither 1
resolution 9 9
b 0.25 0.5 0.75
l 0 0 10
f 1 0 0 1 0 0 0 1
s 0 0 0 0.5
)";

RunResult run_rtpp(const fs::path& dir, const std::string& args) {
    return run_program(RTPP_BINARY, dir, args);
}

// Pixel (x, y)'s red, green and blue in a PFM image (rows from the top).
rt::Spectrum pfm_pixel(const rt::ImageFile& image, int width, int x, int y) {
    const std::size_t at = 3 * (static_cast<std::size_t>(y) * width + x);
    return {image.floats[at], image.floats[at + 1], image.floats[at + 2]};
}

}  // namespace

TEST(nff_by_extension_and_by_from_give_the_same_scene) {
    const fs::path dir = work_dir("nff_cli_same");
    write_file(dir / "x.nff", kNff);
    write_file(dir / "x.txt", kNff);
    const RunResult by_name = run_rtpp(dir, "x.nff");
    CHECK_EQ(by_name.status, 0);
    CHECK_CONTAINS(by_name.out, "\n115 0.25 0.5 0.75\n");
    // The same numbers, whatever the input is called (only its name in the markers differs).
    const auto renamed = [](std::string text, const std::string& name) {
        for (std::size_t at; (at = text.find(name)) != std::string::npos;)
            text.replace(at, name.size(), "NAME");
        return text;
    };
    const RunResult from_stdin = run_rtpp(dir, "--from nff < x.nff");
    CHECK_EQ(from_stdin.status, 0);
    CHECK_EQ(renamed(from_stdin.out, "<stdin>"), renamed(by_name.out, "x.nff"));
    CHECK_EQ(renamed(run_rtpp(dir, "--from=nff - < x.nff").out, "<stdin>"),
             renamed(by_name.out, "x.nff"));
    CHECK_EQ(renamed(run_rtpp(dir, "--from nff x.txt").out, "x.txt"),
             renamed(by_name.out, "x.nff"));
    // Upper case counts too; --from rts overrides the extension.
    write_file(dir / "X.NFF", kNff);
    CHECK_EQ(renamed(run_rtpp(dir, "X.NFF").out, "X.NFF"), renamed(by_name.out, "x.nff"));
    const RunResult as_rts = run_rtpp(dir, "--from rts x.nff");
    CHECK_EQ(as_rts.status, 1);
    CHECK_CONTAINS(as_rts.err, "x.nff:2:6: expected a statement");
    // -o writes the same scene to a file.
    CHECK_EQ(run_rtpp(dir, "x.nff -o x.in").status, 0);
    CHECK_EQ(read_file(dir / "x.in"), by_name.out);
}

TEST(an_nff_scene_renders_through_rt_to_known_pixels) {
    const fs::path dir = work_dir("nff_cli_render");
    write_file(dir / "x.nff", kNff);
    const RunResult r = run_rtpp(dir, "x.nff | '" + rt_binary() + "' - -o x.pfm");
    CHECK_EQ(r.status, 0);
    const rt::ImageFile image = rt::read_image_file(dir / "x.pfm");
    CHECK_EQ(image.floats.size(), std::size_t{9 * 9 * 3});
    if (image.floats.size() != 9 * 9 * 3) return;
    // A corner misses: exactly the background (as a float).
    const rt::Spectrum sky(0.25, 0.5, 0.75);
    CHECK_EQ(show(pfm_pixel(image, 9, 0, 0)), show(sky));
    CHECK_EQ(show(pfm_pixel(image, 9, 8, 8)), show(sky));
    // The middle pixel's centre ray is the axis (NFF's rays go through pixel centres): it
    // meets the sphere head on at (0, 0, 0.5), where the light from (0, 0, 10) falls straight
    // in: kd colour (d.s) = (1, 0, 0), no ambient light.
    CHECK_NEAR(pfm_pixel(image, 9, 4, 4), rt::Spectrum(1, 0, 0), 1e-6);
}

TEST(nff_errors_name_the_nff_file_and_usage_errors_exit_2) {
    const fs::path dir = work_dir("nff_cli_errors");
    write_file(dir / "bad.nff",
               "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\n"
               "resolution 4 4\nf 1 1 1 1 0 0 0 1\ns 0 0 zero 1\n");
    RunResult r = run_rtpp(dir, "bad.nff -o bad.in");
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "bad.nff:9:7: ");
    CHECK(!fs::exists(dir / "bad.in"));  // nothing written on an error
    r = run_rtpp(dir, "--from nff < bad.nff");
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "<stdin>:9:7: ");
    CHECK_EQ(r.out, std::string());
    r = run_rtpp(dir, "--from bogus bad.nff");
    CHECK_EQ(r.status, 2);
    CHECK_CONTAINS(r.err, "rtpp: --from takes 'rts' or 'nff', got 'bogus'");
    CHECK_EQ(run_rtpp(dir, "--from").status, 2);
    r = run_rtpp(dir, "missing.nff");
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "missing.nff: cannot open");
}

namespace {

// Runs rtpp with `args` in `dir`, its output to /dev/null, and returns its peak resident
// memory in KiB (-1 when it did not exit with 0).
long rtpp_peak_kib(const fs::path& dir, const std::vector<std::string>& args) {
    const pid_t pid = ::fork();
    if (pid == 0) {
        if (::chdir(dir.c_str()) != 0) ::_exit(127);
        const int null = ::open("/dev/null", O_RDWR);
        ::dup2(null, 1);
        ::dup2(null, 2);
        std::vector<char*> argv{const_cast<char*>(RTPP_BINARY)};
        for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(RTPP_BINARY, argv.data());
        ::_exit(127);
    }
    int status = 0;
    rusage usage{};
    if (::wait4(pid, &status, 0, &usage) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return -1;
    return usage.ru_maxrss;
}

}  // namespace

// 600,000 spheres (about 23 MB of NFF, 17 MB of scene): the translation goes to a spool that
// keeps 8 MB in memory and the rest in a temporary file, so rtpp's memory does not grow with
// the file, to standard output or to a file alike; and the spooled result is the whole scene.
TEST(a_large_nff_file_streams_through_in_bounded_memory) {
    const fs::path dir = work_dir("nff_cli_large");
    std::string nff =
        "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 9 9\n"
        "l 0 0 10\nf 1 0 0 1 0 0 0 1\n";
    for (int i = 0; i < 600000; ++i)
        nff += "s " + std::to_string(i % 631) + ".25 " + std::to_string(i / 631) + ".5 -7 0.125\n";
    write_file(dir / "big.nff", nff);
    const long to_stdout = rtpp_peak_kib(dir, {"big.nff"});
    const long to_file = rtpp_peak_kib(dir, {"big.nff", "-o", "big.in"});
    CHECK(to_stdout > 0);
    CHECK(to_file > 0);
    std::cout << "  peak: " << to_stdout / 1024 << " MiB to standard output, " << to_file / 1024
              << " MiB to a file\n";
    // The spool's 8 MB, buffers and the program itself; holding the scene would be 17 MB more.
    if (RT_MEASURES_MEMORY) {
        CHECK(to_stdout < 16 * 1024);
        CHECK(to_file < 16 * 1024);
    }
    const std::string scene = read_file(dir / "big.in");
    CHECK(scene.size() > 15u << 20);
    CHECK_CONTAINS(scene.substr(scene.size() - 200), "\n1 0.125 549.25 950.5 -7 106\n");
    std::size_t spheres = 0;
    for (std::size_t at = scene.find("\n1 "); at != std::string::npos;
         at = scene.find("\n1 ", at + 1))
        ++spheres;
    CHECK_EQ(spheres, 600000u);
}
