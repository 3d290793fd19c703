// What a first user of rtimg found: converted files' metadata describes them, a .pgm name
// gets grey PGM (or a refusal for colour), and --max-fraction is a share.
#include <filesystem>
#include <string>

#include "check.h"
#include "cli_util.h"
#include "rt/image_file.h"

namespace fs = std::filesystem;
using namespace rt_test;

namespace {

std::string options_of(const fs::path& file) {
    const rt::ImageFile image = rt::read_image_file(file);
    const std::string* options = image.metadata.find("Options");
    return options != nullptr ? *options : std::string("(none)");
}

}  // namespace

TEST(converted_metadata_describes_the_new_file) {
    const fs::path dir = work_dir("rtimg_findings_metadata");
    write_file(dir / "scene.in", kSmallScene);
    CHECK_EQ(run_rt(dir, "scene.in -o a.png").status, 0);
    CHECK_CONTAINS(options_of(dir / "a.png"), " --bits 8 --gamma linear");
    CHECK_EQ(run_rtimg(dir, "convert --gamma srgb --bits 16 a.png b.png").status, 0);
    const std::string options = options_of(dir / "b.png");
    CHECK_CONTAINS(options, "-d 7 -w 0.01 -m trace -s 1 --bits 16 --gamma srgb");
    CHECK(options.find("--bits 8") == std::string::npos);
    CHECK(options.find("linear") == std::string::npos);
    // Without the options: the input's bits and gamma are kept, and so is the record.
    CHECK_EQ(run_rtimg(dir, "convert b.png c.png").status, 0);
    CHECK_CONTAINS(options_of(dir / "c.png"), "--bits 16 --gamma linear");
}

TEST(a_pgm_name_gets_grey_pgm_or_a_refusal) {
    const fs::path dir = work_dir("rtimg_findings_pgm");
    write_file(dir / "grey.pgm", "P2 3 1 255 0 128 255\n");
    CHECK_EQ(run_rtimg(dir, "convert grey.pgm grey.png").status, 0);
    CHECK_EQ(run_rtimg(dir, "convert grey.png back.pgm").status, 0);
    const std::string back = read_file(dir / "back.pgm");
    CHECK_EQ(back.substr(0, 3), std::string("P5\n"));
    CHECK_EQ(back.substr(back.size() - 3), std::string("\x00\x80\xff", 3));
    write_file(dir / "scene.in", kSmallScene);
    CHECK_EQ(run_rt(dir, "scene.in -o colour.png").status, 0);
    const RunResult r = run_rtimg(dir, "convert colour.png colour.pgm");
    CHECK_EQ(r.status, 2);
    CHECK_CONTAINS(r.err,
                   "'colour.pgm' names PGM, which holds grey, and the image has colour: "
                   "name it .ppm or .png");
    CHECK(!fs::exists(dir / "colour.pgm"));
}

TEST(max_fraction_is_a_share) {
    const fs::path dir = work_dir("rtimg_findings_fraction");
    write_file(dir / "grey.pgm", "P2 3 1 255 0 128 255\n");
    RunResult r = run_rtimg(dir, "diff --max-fraction 2 grey.pgm grey.pgm");
    CHECK_EQ(r.status, 2);
    CHECK_CONTAINS(r.err, "--max-fraction is a share of the pixels, from 0 to 1, got '2'");
    CHECK_EQ(run_rtimg(dir, "diff --max-fraction 1 grey.pgm grey.pgm").status, 0);
}

TEST(an_output_that_is_the_input_is_called_the_input) {
    const fs::path dir = work_dir("rtimg_findings_input");
    write_file(dir / "grey.pgm", "P2 3 1 255 0 128 255\n");
    const RunResult r = run_rtimg(dir, "convert grey.pgm grey.pgm");
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err,
                   "it is the input image 'grey.pgm', which rtimg reads: choose another name");
}
