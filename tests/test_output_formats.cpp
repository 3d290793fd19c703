// rt's image formats through the real binary: the choice by extension or -f, --bits,
// --gamma, the metadata, and usage errors that leave an existing image alone.
#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <string_view>

#include "check.h"
#include "cli_util.h"
#include "batch/cli.h"
#include "rt/image_io.h"
#include "scene/texture.h"

using namespace rt_test;
namespace fs = std::filesystem;

namespace {

// A sphere under a light bright enough to over-expose its highlight (values above 1).
const std::string kScene =
    "102 0 0 5 0 0 0 1 0 0 0 .75 0 12 9\n"
    "101 -3 4 5 80 60 50\n103 .05 .08 .1\n"
    "1 0.9 0.2 0 0 100 .9 .6 .3 .6 20 .8 0 1\n";
constexpr std::size_t kSamples = 12 * 9 * 3;

// The samples after a binary PPM's header (magic, comments, width, height, maxval).
std::string ppm_samples(const std::string& ppm) {
    std::size_t at = 2;
    for (int fields = 0; fields < 3; ++fields) {
        for (;;) {
            while (at < ppm.size() && std::isspace(static_cast<unsigned char>(ppm[at]))) ++at;
            if (at < ppm.size() && ppm[at] == '#') {
                at = ppm.find('\n', at);
                continue;
            }
            break;
        }
        while (at < ppm.size() && std::isdigit(static_cast<unsigned char>(ppm[at]))) ++at;
    }
    return ppm.substr(at + 1);
}

std::string bytes_of(const rt::SampleImage& image) {
    return std::string(image.bytes.begin(), image.bytes.end());
}

fs::path scene_dir(const std::string& name) {
    const fs::path dir = work_dir(name);
    write_file(dir / "scene.in", kScene);
    return dir;
}

// Renders the scene with the options into `file` in `dir` and returns the file.
std::string rendered(const fs::path& dir, const std::string& options, const std::string& file) {
    const RunResult r = run_rt(dir, options + " scene.in -o " + file);
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.err, std::string());
    return read_file(dir / file);
}

float pfm_value(const std::string& pfm, std::size_t header, std::size_t i) {
    std::uint32_t bits = 0;
    for (std::size_t b = 0; b < 4; ++b)
        bits |= std::uint32_t{static_cast<unsigned char>(pfm[header + 4 * i + b])} << (8 * b);
    return std::bit_cast<float>(bits);
}

}  // namespace

TEST(format_by_extension_and_by_f) {
    const fs::path dir = scene_dir("formats");
    const std::string ppm = rendered(dir, "", "out.ppm");
    const std::string png = rendered(dir, "", "out.png");
    const std::string pfm = rendered(dir, "", "OUT.PFM");
    CHECK_EQ(ppm.substr(0, 3), std::string("P6\n"));
    CHECK_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n"));
    const std::string header = "PF\n12 9\n-1.0\n";
    CHECK_EQ(pfm.substr(0, header.size()), header);
    CHECK_EQ(pfm.size(), header.size() + kSamples * 4);
    // The same pixels in PPM and PNG.
    CHECK(bytes_of(rt::decode_png(png).image) == ppm_samples(ppm));
    // PFM holds the values before clamping, bottom row first: where a PFM value exceeds 1
    // the PPM sample is 255, and every other one rounds to the PPM's.
    const std::string samples = ppm_samples(ppm);
    int over = 0;
    for (std::size_t i = 0; i < kSamples; ++i) {
        const std::size_t pixel = i / 3;
        const std::size_t flipped = ((9 - 1 - pixel / 12) * 12 + pixel % 12) * 3 + i % 3;
        const float v = pfm_value(pfm, header.size(), flipped);
        over += v > 1;
        CHECK_EQ(static_cast<int>(static_cast<unsigned char>(samples[i])),
                 v >= 1 ? 255 : static_cast<int>(std::lround(255 * double{v})));
    }
    CHECK(over > 0);
    // -f chooses for standard output and overrides an extension.
    RunResult r = run_rt(dir, "-f png scene.in");
    CHECK_EQ(r.status, 0);
    CHECK(r.out == png);
    CHECK(run_rt(dir, "--format=pfm scene.in -o -").out == pfm);
    CHECK(rendered(dir, "-fppm", "really-ppm.png") == ppm);
    // No extension: PPM, as standard output is.
    CHECK(rendered(dir, "", "noext") == ppm);
    CHECK(run_rt(dir, "scene.in").out == ppm);
}

TEST(bits_16) {
    const fs::path dir = scene_dir("bits16");
    const std::string ppm16 = rendered(dir, "--bits 16", "b.ppm");
    CHECK_CONTAINS(ppm16, "\n12 9\n65535\n");
    const std::string samples16 = ppm_samples(ppm16);
    CHECK_EQ(samples16.size(), kSamples * 2);
    const rt::DecodedImage png16 = rt::decode_png(rendered(dir, "--bits=16", "b.png"));
    CHECK_EQ(png16.image.bits, 16);
    CHECK(bytes_of(png16.image) == samples16);
    // Each 16-bit sample, scaled to 8 bits, is within rounding of the 8-bit one.
    const std::string samples8 = ppm_samples(rendered(dir, "", "a.ppm"));
    for (std::size_t i = 0; i < samples8.size(); ++i) {
        const unsigned v16 = static_cast<unsigned char>(samples16[2 * i]) * 256u +
                             static_cast<unsigned char>(samples16[2 * i + 1]);
        CHECK_NEAR(v16 / 65535.0 * 255, static_cast<unsigned char>(samples8[i]), 0.51);
    }
    // rt reads its own 16-bit output as a texture.
    CHECK_EQ(rt::read_texture(dir / "b.ppm").width, 12);
}

TEST(gamma_option) {
    const fs::path dir = scene_dir("gamma");
    const std::string linear = rendered(dir, "--no-metadata", "linear.ppm");
    CHECK(rendered(dir, "--no-metadata --gamma 1", "one.ppm") == linear);
    CHECK(rendered(dir, "--no-metadata --gamma linear", "lin.ppm") == linear);
    // Every sample is where the transfer function takes the linear one, within the linear
    // image's own rounding.
    const std::string lin = ppm_samples(linear);
    const std::string srgb = ppm_samples(rendered(dir, "--no-metadata --gamma srgb", "s.ppm"));
    const std::string g22 = ppm_samples(rendered(dir, "--no-metadata --gamma 2.2", "g.ppm"));
    CHECK(srgb != lin);
    const rt::Gamma kinds[] = {{rt::Gamma::Kind::srgb, 1}, {rt::Gamma::Kind::power, 2.2}};
    for (std::size_t i = 0; i < lin.size(); ++i) {
        const double l = static_cast<unsigned char>(lin[i]);
        const std::string* encoded[] = {&srgb, &g22};
        for (std::size_t k = 0; k < 2; ++k) {
            const double low = rt::encode_gamma(std::max(0.0, l - 0.5) / 255, kinds[k]) * 255;
            const double high = rt::encode_gamma(std::min(255.0, l + 0.5) / 255, kinds[k]) * 255;
            const double e = static_cast<unsigned char>((*encoded[k])[i]);
            CHECK(e >= std::floor(low) && e <= std::ceil(high));
        }
    }
    // PFM ignores gamma: it holds the raster's values.
    CHECK(rendered(dir, "", "a.pfm") == rendered(dir, "--gamma srgb", "b.pfm"));
}

TEST(metadata_records_what_made_the_image) {
    const fs::path dir = scene_dir("metadata");
    const std::string ppm = rendered(dir, "-d 3 -w 0.05 -s 2 --no-shadows --gamma srgb", "m.ppm");
    CHECK_EQ(ppm.substr(0, 3), std::string("P6\n"));
    CHECK_CONTAINS(ppm, "\n# Software: rt " RT_VERSION "\n");
    CHECK_CONTAINS(ppm, "\n# Scene: scene.in\n");
    CHECK_CONTAINS(ppm,
                   "\n# Options: -d 3 -w 0.05 -m trace -s 2 --no-shadows --bits 8 --gamma srgb\n");
    // Options that do not change pixels are not recorded; -a is.
    const rt::DecodedImage png =
        rt::decode_png(rendered(dir, "-j 2 --no-bvh -a 0.1 --no-reflection -m normal", "n.png"));
    CHECK(*png.metadata.find("Software") == "rt " RT_VERSION);
    CHECK(*png.metadata.find("Scene") == "scene.in");
    CHECK(*png.metadata.find("Options") ==
          "-d 7 -w 0.01 -m normal -s 3 -a 0.1 --no-reflection --bits 8 --gamma linear");
    CHECK_CONTAINS(run_rt(dir, "-o - < scene.in").out, "\n# Scene: <stdin>\n");

    // The pixels are those of the original format, which --no-metadata writes byte for byte.
    const std::string with = rendered(dir, "", "with.ppm");
    const std::string without = rendered(dir, "--no-metadata", "without.ppm");
    CHECK_EQ(without.substr(0, 12), std::string("P6\n12 9\n255\n"));
    CHECK_EQ(without.size(), 12u + kSamples);
    CHECK(ppm_samples(with) == ppm_samples(without));
    CHECK(with.substr(with.size() - kSamples) == without.substr(12));
    // rt reads its own commented output back as a texture, to the same values.
    const rt::Image a = rt::read_texture(dir / "with.ppm");
    const rt::Image b = rt::read_texture(dir / "without.ppm");
    CHECK(a.values == b.values);
    CHECK(rt::decode_png(read_file(dir / "n.png")).metadata.entries.size() == 3);
    CHECK(rt::decode_png(rendered(dir, "--no-metadata", "bare.png")).metadata.entries.empty());
}

TEST(format_usage_errors_exit_2_before_rendering) {
    const fs::path dir = scene_dir("format_usage");
    const std::string bad[] = {"scene.in -o out.jpg",
                               "scene.in -o out.tmp",
                               "-f gif scene.in -o out.ppm",
                               "-f scene.in",
                               "--bits 12 scene.in -o out.png",
                               "--bits 0 scene.in -o out.png",
                               "--bits scene.in",
                               "--bits 16 scene.in -o out.pfm",
                               "-f pfm --bits 8 scene.in -o out.ppm",
                               "--gamma 0 scene.in -o out.png",
                               "--gamma -2.2 scene.in -o out.png",
                               "--gamma abc scene.in -o out.png",
                               "--gamma nan scene.in -o out.png",
                               "--no-metadata=1 scene.in -o out.png"};
    const std::string keep = "previous image, must survive";
    for (const std::string& args : bad) {
        for (const char* name : {"out.ppm", "out.png", "out.jpg", "out.tmp", "out.pfm"})
            write_file(dir / name, keep);
        const RunResult r = run_rt(dir, args);
        CHECK_EQ(r.status, 2);
        CHECK_CONTAINS(r.err, "Try 'rt --help'");
        CHECK(r.out.empty());
        for (const char* name : {"out.ppm", "out.png", "out.jpg", "out.tmp", "out.pfm"})
            CHECK(read_file(dir / name) == keep);
    }
    CHECK_CONTAINS(run_rt(dir, "scene.in -o out.jpg").err,
                   "rt: cannot tell the image format of 'out.jpg' from its extension");
    CHECK_CONTAINS(run_rt(dir, "-f gif scene.in").err, "-f expects ppm, png or pfm, got 'gif'");
    CHECK_CONTAINS(run_rt(dir, "--bits 12 scene.in").err, "--bits expects 8 or 16, got '12'");
    CHECK_CONTAINS(run_rt(dir, "--gamma 0 scene.in").err,
                   "--gamma expects linear, srgb or a number > 0, got '0'");
    CHECK_CONTAINS(run_rt(dir, "--bits 16 scene.in -o out.pfm").err,
                   "--bits does not apply to PFM");
    // An unknown extension with -f is fine: the user said what to write.
    CHECK(rt::decode_png(rendered(dir, "-f png", "out.jpg")).image.width == 12);
}

TEST(parse_command_line_formats) {
    rt::CommandLine cl = rt::parse_command_line({"-o", "x.PNG", "--bits", "16", "--gamma=srgb"});
    CHECK(cl.image.format == rt::ImageFormat::png);
    CHECK_EQ(cl.image.bits, 16);
    CHECK(cl.image.gamma.kind == rt::Gamma::Kind::srgb);
    cl = rt::parse_command_line({});
    CHECK(cl.image.format == rt::ImageFormat::ppm);
    CHECK_EQ(cl.image.bits, 8);
    CHECK(cl.image.gamma.kind == rt::Gamma::Kind::linear);
    CHECK(cl.metadata);
    CHECK(rt::parse_command_line({"-f", "pfm", "-o", "a.png"}).image.format ==
          rt::ImageFormat::pfm);
    CHECK(rt::parse_command_line({"-o", "a.pfm", "--gamma", "2"}).image.gamma.exponent == 2);
    CHECK(rt::image_metadata(rt::parse_command_line({"--no-metadata"})).entries.empty());
    // PFM records no bits or gamma: they do not touch it.
    CHECK(*rt::image_metadata(rt::parse_command_line({"-o", "a.pfm", "s.in"})).find("Options") ==
          "-d 7 -w 0.01 -m trace -s 1");
}

TEST(help_lists_the_format_options) {
    const fs::path dir = work_dir("format_help");
    const RunResult r = run_rt(dir, "--help");
    CHECK_CONTAINS(r.out, "-f, --format FMT");
    CHECK_CONTAINS(r.out, "--bits N");
    CHECK_CONTAINS(r.out, "--gamma G");
    CHECK_CONTAINS(r.out, "--no-metadata");
}
