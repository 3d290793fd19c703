// rtpp reading NFF from its command line: by the .nff extension, or --from nff for standard
// input and any name; the result rendered by rt, checked pixel by pixel.
#include <cmath>
#include <filesystem>
#include <string>

#include "check.h"
#include "cli_util.h"
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
