// rtimg: diff's statistics against a hand-computed case, every diff flag, merges of random
// tilings byte-identical to the whole render, merge errors, convert round trips and info.
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "check.h"
#include "cli_util.h"
#include "rt/image_file.h"

namespace fs = std::filesystem;
using namespace rt_test;

namespace {

// A 2 x 2 binary PPM from its twelve samples.
std::string ppm(const std::vector<int>& samples) {
    std::string out = "P6\n2 2\n255\n";
    for (const int s : samples) out += static_cast<char>(s);
    return out;
}

const std::string kScene = std::string(RT_SOURCE_DIR) + "/scenes/sphere-light.in";
// Small and quick, yet with an area light and edges.
const std::string kRender = "-q --size 40x30 '" + kScene + "'";

// Cuts `r` at random into pieces (a guillotine tiling), some of them one pixel wide.
void tile(std::mt19937& random, int x0, int x1, int y0, int y1, int depth,
          std::vector<std::string>& regions) {
    const bool split_x = random() % 2 == 0;
    const int length = split_x ? x1 - x0 : y1 - y0;
    if (depth == 0 || length < 2) {
        regions.push_back(join(x0, ",", x1, ",", y0, ",", y1));
        return;
    }
    const int cut = (split_x ? x0 : y0) + 1 + static_cast<int>(random() % (length - 1));
    if (split_x) {
        tile(random, x0, cut, y0, y1, depth - 1, regions);
        tile(random, cut, x1, y0, y1, depth - 1, regions);
    } else {
        tile(random, x0, x1, y0, cut, depth - 1, regions);
        tile(random, x0, x1, cut, y1, depth - 1, regions);
    }
}

}  // namespace

TEST(diff_statistics_match_a_hand_computed_case) {
    const fs::path dir = work_dir("rtimg-diff");
    // Component differences: (10, 0, 0), (0, 3, 0), (0, 0, 0), (1, 1, 1).
    write_file(dir / "a.ppm", ppm({0, 0, 0, 0, 0, 0, 50, 60, 70, 200, 200, 200}));
    write_file(dir / "b.ppm", ppm({10, 0, 0, 0, 3, 0, 50, 60, 70, 201, 201, 201}));
    const RunResult r = run_rtimg(dir, "diff a.ppm b.ppm");
    CHECK_EQ(r.status, 1);  // 3 of 4 pixels differ, more than --max-fraction 0
    CHECK_CONTAINS(r.out, "size: 2x2\n");
    CHECK_CONTAINS(r.out, "largest difference: 10 levels\n");
    CHECK_CONTAINS(r.out, "differing pixels: 3 of 4 (75%) by more than 0 levels\n");
    // Mean |d| = (10 + 3 + 3) / 12; RMSE = sqrt((100 + 9 + 3) / 12); PSNR = 20 log10(255/RMSE).
    CHECK_CONTAINS(r.out, "mean absolute error: 1.33333 levels\n");
    CHECK_CONTAINS(r.out, "RMSE: 3.05505 levels\n");
    CHECK_CONTAINS(r.out, join("PSNR: ", "38.4304", " dB\n"));
    CHECK_NEAR(20 * std::log10(255 / std::sqrt(112.0 / 12)), 38.4304, 1e-4);
    CHECK_CONTAINS(r.out, "result: fail (share 0.75 > --max-fraction 0)\n");

    // --tolerance: a pixel differs when a component is more than T away.
    CHECK_CONTAINS(run_rtimg(dir, "diff --tolerance 2 a.ppm b.ppm").out,
                   "differing pixels: 2 of 4 (50%) by more than 2 levels");
    CHECK_CONTAINS(run_rtimg(dir, "diff --tolerance=3 a.ppm b.ppm").out,
                   "differing pixels: 1 of 4 (25%) by more than 3 levels");
    CHECK_CONTAINS(run_rtimg(dir, "diff --tolerance 10 a.ppm b.ppm").out,
                   "differing pixels: 0 of 4 (0%)");
    // --max-fraction: the share may reach F, not pass it.
    CHECK_EQ(run_rtimg(dir, "diff --tolerance 2 --max-fraction 0.5 a.ppm b.ppm").status, 0);
    CHECK_EQ(run_rtimg(dir, "diff --tolerance 2 --max-fraction 0.49 a.ppm b.ppm").status, 1);
    CHECK_EQ(run_rtimg(dir, "diff --tolerance 10 a.ppm b.ppm").status, 0);
    CHECK_EQ(run_rtimg(dir, "diff a.ppm a.ppm").status, 0);
    CHECK_CONTAINS(run_rtimg(dir, "diff a.ppm a.ppm").out, "PSNR: inf dB");
}

TEST(diff_writes_a_heat_map) {
    const fs::path dir = work_dir("rtimg-heat");
    write_file(dir / "a.ppm", ppm({0, 0, 0, 0, 0, 0, 40, 40, 40, 200, 200, 200}));
    write_file(dir / "b.ppm", ppm({10, 0, 0, 0, 3, 0, 40, 40, 40, 201, 201, 201}));
    CHECK_EQ(run_rtimg(dir, "diff --tolerance 2 -o heat.png a.ppm b.ppm").status, 1);
    const rt::ImageFile heat = rt::read_image_file(dir / "heat.png");
    const auto rgb = [&](int x, int y) {
        return join(heat.samples.sample(x, y, 0), " ", heat.samples.sample(x, y, 1), " ",
                    heat.samples.sample(x, y, 2));
    };
    CHECK_EQ(rgb(0, 0), "116 0 0");   // 10 > 2: red, 96 + 159 (10 - 2) / 64
    CHECK_EQ(rgb(1, 0), "98 0 0");    // 3 > 2: 96 + 159 / 64
    CHECK_EQ(rgb(0, 1), "10 10 10");  // the same: a's grey, a quarter as bright
    CHECK_EQ(rgb(1, 1), "0 0 128");   // 1, within the tolerance
    // The option conventions rt has: -oFILE, --output=FILE, and "--" before a name with '-'.
    fs::copy_file(dir / "b.ppm", dir / "-b.ppm");
    CHECK_EQ(run_rtimg(dir, "diff --tolerance=2 -oheat2.png a.ppm b.ppm").status, 1);
    CHECK(read_file(dir / "heat2.png") == read_file(dir / "heat.png"));
    CHECK_EQ(run_rtimg(dir, "diff --tolerance 2 --output=heat3.png -- a.ppm -b.ppm").status, 1);
    CHECK(read_file(dir / "heat3.png") == read_file(dir / "heat.png"));
}

TEST(diff_compares_across_formats_and_bit_depths_and_reports_errors) {
    const fs::path dir = work_dir("rtimg-diff-errors");
    write_file(dir / "a.ppm", ppm({0, 0, 0, 0, 0, 0, 50, 60, 70, 200, 200, 200}));
    // The same image in 16 bits (v * 257) and as plain text.
    std::string wide = "P6\n2 2\n65535\n";
    for (const int s : {0, 0, 0, 0, 0, 0, 50, 60, 70, 200, 200, 200})
        wide += std::string{static_cast<char>(s * 257 >> 8), static_cast<char>(s * 257 & 255)};
    write_file(dir / "wide.ppm", wide);
    write_file(dir / "plain.ppm", "P3\n# Scene: x\n2 2\n255\n0 0 0 0 0 0\n50 60 70 200 200 200\n");
    CHECK_EQ(run_rtimg(dir, "diff a.ppm wide.ppm").status, 0);
    CHECK_EQ(run_rtimg(dir, "diff plain.ppm wide.ppm").status, 0);
    write_file(dir / "small.ppm", "P6\n1 1\n255\nabc");
    const RunResult sizes = run_rtimg(dir, "diff a.ppm small.ppm");
    CHECK_EQ(sizes.status, 1);
    CHECK_CONTAINS(sizes.out, "different sizes");
    CHECK_EQ(run_rtimg(dir, "diff a.ppm missing.ppm").status, 2);
    CHECK_EQ(run_rtimg(dir, "diff a.ppm").status, 2);
    CHECK_EQ(run_rtimg(dir, "diff --tolerance -1 a.ppm a.ppm").status, 2);
    CHECK_EQ(run_rtimg(dir, "diff --bogus a.ppm a.ppm").status, 2);
    CHECK_EQ(run_rtimg(dir, "diff -o heat.xyz a.ppm a.ppm").status, 2);
    CHECK_EQ(run_rtimg(dir, "frobnicate").status, 2);
}

TEST(merging_random_tilings_gives_the_whole_render_byte_for_byte) {
    const fs::path dir = work_dir("rtimg-merge");
    std::mt19937 random(42);
    const char* variants[] = {"-o whole.png", "-a 0.02 -o whole.ppm", "--bits 16 -o whole.png",
                              "--no-metadata -j 3 -o whole.ppm"};
    for (const std::string variant : variants) {
        CHECK_EQ(run_rt(dir, kRender + " " + variant).status, 0);
        const std::string extension = variant.substr(variant.size() - 4);
        std::vector<std::string> regions;
        tile(random, 0, 40, 0, 30, 3, regions);
        std::string pieces;
        for (std::size_t i = 0; i < regions.size(); ++i) {
            const std::string name = join("piece", i, extension);
            const std::string options = variant.substr(0, variant.find("-o "));
            CHECK_EQ(run_rt(dir, join(kRender, " ", options, " -j ", 1 + i % 3, " --region ",
                                      regions[i], " -o ", name))
                         .status,
                     0);
            pieces += " " + name;
        }
        const RunResult merged = run_rtimg(dir, "merge" + pieces + " -o merged" + extension);
        CHECK_EQ(merged.status, 0);
        CHECK_EQ(merged.err, "");
        if (read_file(dir / ("merged" + extension)) != read_file(dir / ("whole" + extension)))
            record_failure(__FILE__, __LINE__,
                           join(variant, ": the merge of", pieces, " differs from the whole"));
    }
}

TEST(merge_names_gaps_overlaps_and_mismatched_pieces) {
    const fs::path dir = work_dir("rtimg-merge-errors");
    const auto render = [&](const std::string& args) { CHECK_EQ(run_rt(dir, args).status, 0); };
    render(kRender + " --region 0,40,0,10 -o top.ppm");
    render(kRender + " --region 0,40,10,30 -o bottom.ppm");
    render(kRender + " --region 0,40,12,30 -o short.ppm");
    render(kRender + " --region 0,40,8,30 -o tall.ppm");
    render(kRender + " -o whole.ppm");
    render("-q --size 40x20 '" + kScene + "' --region 0,40,10,20 -o other-size.ppm");
    render(kRender + " -d 2 --region 0,40,10,30 -o other-options.ppm");
    render(kRender + " --region 0,40,10,30 -o bottom.png");
    const auto fails = [&](const std::string& pieces, const std::string& message) {
        const RunResult r = run_rtimg(dir, "merge " + pieces + " -o out.ppm");
        CHECK_EQ(r.status, 1);
        CHECK_CONTAINS(r.err, message);
        CHECK(!fs::exists(dir / "out.ppm"));
    };
    fails("top.ppm short.ppm",
          "the pieces leave a gap: 80 pixels within columns 0-39, rows 10-11 of the 40x30 image "
          "are in no piece");
    fails("top.ppm tall.ppm",
          "pieces overlap: columns 0-39, rows 8-9 are in both top.ppm and tall.ppm");
    fails("top.ppm other-size.ppm",
          "other-size.ppm is a region of a 40x20 image, but top.ppm of a 40x30 one");
    fails("top.ppm other-options.ppm", "other-options.ppm was not made like top.ppm (Options");
    fails("top.ppm bottom.png", "bottom.png is png, 8 bits, 3 channels, but top.ppm is ppm");
    fails("top.ppm whole.ppm", "whole.ppm records no region");
    // A piece of another scene.
    write_file(dir / "small.in", kSmallScene);
    render("-q --size 40x30 small.in --region 0,40,10,30 -o other-scene.ppm");
    fails("top.ppm other-scene.ppm", "(Scene '");
    // The region's record says one size, the pixels another.
    std::string lying = read_file(dir / "top.ppm");
    lying.replace(lying.find("Region: 0,40,0,10"), 17, "Region: 0,40,0,11");
    write_file(dir / "lying.ppm", lying);
    fails("lying.ppm bottom.ppm", "lying.ppm is 40x10 pixels, but its region");
    CHECK_EQ(run_rtimg(dir, "merge top.ppm bottom.ppm").status, 2);  // no -o
    CHECK_EQ(run_rtimg(dir, "merge top.ppm bottom.ppm -o out.ppm").status, 0);
    CHECK(read_file(dir / "out.ppm") == read_file(dir / "whole.ppm"));
}

TEST(convert_round_trips) {
    const fs::path dir = work_dir("rtimg-convert");
    CHECK_EQ(run_rt(dir, kRender + " -o a.png").status, 0);
    CHECK_EQ(run_rt(dir, kRender + " -o a.ppm").status, 0);
    CHECK_EQ(run_rt(dir, kRender + " --bits 16 -o a16.png").status, 0);
    CHECK_EQ(run_rt(dir, kRender + " -o a.pfm").status, 0);
    CHECK_EQ(run_rt(dir, kRender + " --gamma srgb -o srgb.png").status, 0);
    const auto convert = [&](const std::string& args) {
        CHECK_EQ(run_rtimg(dir, "convert " + args).status, 0);
    };
    // PNG and PPM hold the same samples and metadata: each converts to the other exactly.
    convert("a.png b.ppm");
    CHECK(read_file(dir / "b.ppm") == read_file(dir / "a.ppm"));
    convert("b.ppm b.png");
    CHECK(read_file(dir / "b.png") == read_file(dir / "a.png"));
    convert("--plain a.ppm p3.ppm");
    CHECK_EQ(read_file(dir / "p3.ppm").substr(0, 3), "P3\n");
    convert("p3.ppm back.ppm");
    CHECK(read_file(dir / "back.ppm") == read_file(dir / "a.ppm"));
    convert("a16.png b16.ppm");
    convert("b16.ppm b16.png");
    CHECK(read_file(dir / "b16.png") == read_file(dir / "a16.png"));
    convert("a.pfm b.pfm");
    CHECK(read_file(dir / "b.pfm") == read_file(dir / "a.pfm"));
    // From the floats, --bits and --gamma do what rt's own options do (to within the
    // rounding of 32-bit floats).
    convert("--gamma srgb a.pfm c.png");
    CHECK_CONTAINS(run_rtimg(dir, "diff --tolerance 1 c.png srgb.png").out,
                   "by more than 1 levels");
    CHECK_EQ(run_rtimg(dir, "diff --tolerance 1 c.png srgb.png").status, 0);
    convert("--bits 16 a.pfm c16.ppm");
    CHECK_EQ(rt::read_image_file(dir / "c16.ppm").bits(), 16);
    CHECK_EQ(run_rtimg(dir, "convert --bits 16 a.png c.pfm").status, 2);
    CHECK_EQ(run_rtimg(dir, "convert --plain a.png c.png").status, 2);
    CHECK_EQ(run_rtimg(dir, "convert a.png c.gif").status, 2);
    CHECK_EQ(run_rtimg(dir, "convert a.png a.png").status, 1);  // never over its input
}

TEST(info_describes_an_image) {
    const fs::path dir = work_dir("rtimg-info");
    write_file(dir / "a.ppm",
               "P6\n# Software: rt 9\n# Scene: s.in\n# Region: 1,3,0,2\n"
               "# Full-Size: 4x2\n2 2\n255\n" +
                   ppm({0, 10, 20, 2, 12, 22, 4, 14, 24, 6, 16, 26}).substr(11));
    const RunResult r = run_rtimg(dir, "info a.ppm");
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.out,
             "file: a.ppm\nformat: ppm (P6)\nsize: 2x2\nbit depth: 8, 3 channels\n"
             "region: 1,3,0,2 of a 4x2 image\nmade by: rt 9\nScene: s.in\n"
             "channel  min  max  mean\nred  0  6  3\ngreen  10  16  13\nblue  20  26  23\n");
    write_file(dir / "g.pfm", std::string("Pf\n1 1\n-1.0\n") + std::string("\0\0\x80\x3f", 4));
    CHECK_CONTAINS(run_rtimg(dir, "info g.pfm").out,
                   "format: pfm (Pf)\nsize: 1x1\nbit depth: 32 (float), 3 channels\n"
                   "region: none (a whole image)\nmade by: unknown\n");
    CHECK_CONTAINS(run_rtimg(dir, "info g.pfm").out, "red  1  1  1\n");
    CHECK_EQ(run_rtimg(dir, "info missing.png").status, 1);
    // Metadata is the file's to choose: shown escaped, so it cannot drive the terminal.
    write_file(dir / "evil.ppm",
               "P6\n# Software: \x1b]0;owned\x07\n# Scene: a\x1b[2Jb\n1 1\n255\nabc");
    const RunResult evil = run_rtimg(dir, "info evil.ppm");
    CHECK_EQ(evil.status, 0);
    CHECK_CONTAINS(evil.out, "made by: \\x1b]0;owned\\x07\nScene: a\\x1b[2Jb\n");
    CHECK(evil.out.find('\x1b') == std::string::npos);
}

TEST(png_files_another_encoder_wrote_decode_to_its_ppm_pixels) {
    const fs::path dir = fs::path(RT_SOURCE_DIR) / "tests" / "fixtures" / "png";
    const struct {
        const char* png;
        const char* reference;
        int bits;
        int channels;
    } cases[] = {
        {"rgb-q0.png", "source.ppm", 8, 3},  {"rgb-q50.png", "source.ppm", 8, 3},
        {"rgb-q95.png", "source.ppm", 8, 3}, {"rgb-interlaced.png", "source.ppm", 8, 3},
        {"grey.png", "grey.pgm", 8, 1},      {"palette.png", "palette.ppm", 8, 3},
        {"rgb16.png", "rgb16.ppm", 16, 3},   {"grey16-interlaced.png", "grey16.pgm", 16, 1}};
    for (const auto& c : cases) {
        const rt::ImageFile png = rt::read_image_file(dir / c.png);
        const rt::ImageFile reference = rt::read_image_file(dir / c.reference);
        CHECK_EQ(png.bits(), c.bits);
        CHECK_EQ(png.channels(), c.channels);
        if (png.samples.bytes != reference.samples.bytes)
            record_failure(__FILE__, __LINE__, join(c.png, " does not decode to ", c.reference));
    }
}
