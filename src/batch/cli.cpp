#include "batch/cli.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string_view>

#include "common/message_text.h"  // values echoed in messages are escaped as tokens are
#include "rt/limits.h"            // the resolution limits

namespace rt {

namespace {

// The largest values the numeric options take: enough for any sensible render, small
// enough that no option alone can make rt run for ever or allocate without bound. Past 64
// reflections a ray keeps under 0.1% of its weight unless every surface it meets is a perfect
// mirror, and 64 nested mirror images are far below a pixel.
constexpr int kMaxDepthOption = 64;
constexpr int kMaxSamplesOption = 64;
constexpr int kMaxThreadsOption = 1024;

// WxH, each side and the whole within the limits the viewer has in a scene.
ImageSize parse_size(const std::string& text) {
    const auto x = text.find('x');
    const auto bad = [&] {
        return UsageError{"--size expects WIDTHxHEIGHT in pixels (such as 640x480), got " +
                          quote_token(text)};
    };
    if (x == std::string::npos) throw bad();
    ImageSize size;
    const auto side = [&](std::string_view digits, int& out) {
        const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), out);
        if (digits.empty() || ptr != digits.data() + digits.size() ||
            ec == std::errc::invalid_argument)
            throw bad();
        if (ec == std::errc::result_out_of_range || out < 1 || out > kMaxResolution)
            throw UsageError{"--size " + show_token(text) +
                             " is out of range: each side must be from 1 to " +
                             std::to_string(kMaxResolution) + " pixels"};
    };
    const std::string_view whole(text);
    side(whole.substr(0, x), size.width);
    side(whole.substr(x + 1), size.height);
    if (static_cast<long>(size.width) * size.height > kMaxPixels)
        throw UsageError{"--size " + show_token(text) + " is out of range: at most " +
                         std::to_string(kMaxPixels) + " pixels in all"};
    return size;
}

// x0,x1,y0,y1: half-open pixel bounds, as pbrt's --pixelbounds. Whether they fit the image
// is known only once the scene is read.
PixelRect parse_region(const std::string& text) {
    const auto bad = [&] {
        return UsageError{"--region expects x0,x1,y0,y1 (whole numbers, x0 < x1, y0 < y1), got " +
                          quote_token(text)};
    };
    int v[4] = {};
    const char* p = text.data();
    const char* end = p + text.size();
    for (int i = 0; i < 4; ++i) {
        if (i > 0 && (p == end || *p++ != ',')) throw bad();
        const auto [ptr, ec] = std::from_chars(p, end, v[i]);
        if (ec != std::errc() || v[i] < 0) throw bad();
        p = ptr;
    }
    if (p != end) throw bad();
    const PixelRect region{v[0], v[2], v[1], v[3]};
    if (region.empty())
        throw UsageError{"--region " + show_token(text) +
                         " is empty: it needs x0 < x1 and y0 < y1"};
    return region;
}

ImageFormat parse_format(const std::string& text) {
    if (const auto format = parse_format_name(text)) return *format;
    throw UsageError{"-f expects ppm, png or pfm, got " + quote_token(text)};
}

// The format the output's name asks for; a name without an extension is PPM, as standard
// output is, but an extension rt does not write is refused rather than mislabelled.
ImageFormat format_of_output(const std::string& output) {
    if (output == "-") return ImageFormat::ppm;
    bool has_extension = false;
    if (const auto format = format_from_extension(output, &has_extension)) return *format;
    if (!has_extension) return ImageFormat::ppm;
    throw UsageError{"cannot tell the image format of " + quote_token(output, kShowWhole) +
                     " from its extension: name it .ppm, .png or .pfm, or give -f ppm|png|pfm"};
}

const char* mode_name(RenderMode mode) {
    switch (mode) {
        case RenderMode::trace:
            return "trace";
        case RenderMode::depth:
            return "depth";
        case RenderMode::colour:
            return "colour";
        case RenderMode::normal:
            return "normal";
    }
    return "?";
}

RenderMode parse_mode(const std::string& text) {
    if (text == "trace") return RenderMode::trace;
    if (text == "depth") return RenderMode::depth;
    if (text == "colour" || text == "color") return RenderMode::colour;
    if (text == "normal") return RenderMode::normal;
    throw UsageError{"-m expects trace, depth, colour or normal, got " + quote_token(text)};
}

// The parts of the illumination model, each with the switch that turns it off.
std::array<std::pair<bool, const char*>, 6> switch_names(const RenderOptions& r) {
    return {{{r.ambient, "--no-ambient"},
             {r.diffuse, "--no-diffuse"},
             {r.specular, "--no-specular"},
             {r.shadows, "--no-shadows"},
             {r.reflection, "--no-reflection"},
             {r.refraction, "--no-refraction"}}};
}

void set_input(CommandLine& cl, bool& have_input, const std::string& arg) {
    if (have_input)
        throw UsageError{"more than one scene file given (" + quote_token(cl.input, kShowWhole) +
                         " and " + quote_token(arg, kShowWhole) + ")"};
    cl.input = arg;
    have_input = true;
}

}  // namespace

const char* usage_text() {
    return R"(usage: rt [options] [--] [scene]

Renders a scene in rt's numeric scene format to a PPM, PNG or PFM image.
The scene is read from the file named, or from standard input when it is
'-' or absent.

options:
  -o, --output FILE   write the image to FILE ('-', the default: standard output,
                      refused when it is a terminal); its extension (.ppm, .png,
                      .pfm) chooses the format. A file is replaced only once the
                      image is complete; devices, FIFOs and sockets are written
                      in place (-o /dev/null is safe)
  -f, --format FMT    ppm, png or pfm, whatever FILE is called (default: from
                      FILE's extension; ppm for standard output or no extension)
      --bits N        8 (default) or 16 bits per sample (PPM and PNG)
      --gamma G       how values in [0, 1] are written: linear (default, as
                      round(255 c)), srgb (the sRGB transfer function), or a
                      number G > 0 for c^(1/G); PFM is always linear
      --no-metadata   do not record rt's version, the scene and the options in
                      the image (a PPM comment or a PNG text chunk)
  -M, --depend FILE   also write a make rule to FILE, once the image is written:
                      the image depends on the scene, its textures and mesh files
  -d, --depth N       maximum recursion depth for reflected and refracted rays
                      (default 7; 0 traces no secondary rays)
  -w, --weight W      do not trace rays whose weight is below W (default 0.01)
  -m, --mode MODE     trace (default), depth, colour (or color), normal
  -s, --samples N     N x N samples per pixel on a grid centred on the
                      pixel's one ray (default 1)
  -a, --adaptive T    adaptive supersampling: one ray per pixel, and N x N
                      (-s N, default 3) only where a pixel differs from a
                      neighbour by more than T in some colour component
                      (compared clamped to [0, 1])
  -j, --threads N     worker threads (default: one per hardware thread, or under
                      make -jN one plus the job slots free at the start);
                      the image is the same whatever N is
      --size WxH      render W x H pixels instead of the viewer's resolution; the
                      field of view stays (rt warns when pixels become non-square)
      --region x0,x1,y0,y1
                      render only columns x0 to x1-1 and rows y0 to y1-1 of the
                      full image, each pixel exactly as the whole render has it;
                      the file records the region and the full size (PPM and
                      PNG only), for rtimg merge
      --checkpoint FILE
                      keep finished rows in FILE while rendering (flushed to disk
                      every few seconds and when rt is interrupted); removed once
                      the image is written. FILE must not exist yet, unless
                      --resume is given
      --resume        continue from --checkpoint FILE: render only the rows it
                      lacks, for exactly the image an uninterrupted render gives;
                      refused when FILE is for another scene or other options
                      (without FILE, rt renders from the start and says so)
  -r, --read-only     read and check the scene, print a summary, render nothing
  -q, --quiet         print nothing on stderr but errors
      --progress      show progress even when stderr is not a terminal (a line
                      every 5 seconds); on a terminal it is shown anyway
      --stats         print times, ray counts, intersection tests, threads and
                      peak memory on stderr at the end
      --no-ambient    leave out the ambient term
      --no-diffuse    leave out diffuse reflection of the lights
      --no-specular   leave out specular highlights
      --no-shadows    do not test shadow rays: every light reaches every point
      --no-reflection do not trace reflected rays
      --no-refraction do not trace refracted rays
      --no-bvh        test every ray against every object in turn instead of
                      using the bounding volume hierarchy (same image, slower)
  -h, --help          print this help and exit
  -V, --version       print the version and exit
  --                  end of options: the next argument is the scene, even
                      one that starts with '-'

A number may be written with a leading '+'.

environment: MAKEFLAGS (GNU make's jobserver: see -j), RT_DEBUG=threads (print
the thread count and jobserver tokens on standard error)

exit status: 0 success, 1 scene or input/output error, 2 usage error; SIGINT,
SIGTERM and SIGHUP remove the temporary file (a checkpoint is flushed and kept)
and end rt as killed by them
)";
}

CommandLine parse_command_line(const std::vector<std::string>& args) {
    CommandLine cl;
    bool have_input = false;
    bool have_samples = false;
    std::optional<ImageFormat> format;
    bool have_bits = false;
    OptionReader options(args, "dwmsajofM");
    while (options.next()) {
        if (!options.is_option()) {
            set_input(cl, have_input, options.argument());
            continue;
        }
        const std::string& arg = options.argument();
        const auto take_value = [&] { return options.value(); };
        auto flag = [&](bool& target, bool setting) {
            options.no_value();
            target = setting;
        };

        RenderOptions& r = cl.render;
        if (arg == "-o" || arg == "--output") {
            cl.output = take_value();
            if (cl.output.empty()) throw UsageError{"-o needs a file name"};
        } else if (arg == "-f" || arg == "--format") {
            format = parse_format(take_value());
            cl.format_given = true;
        } else if (arg == "--bits") {
            const std::string bits = take_value();
            if (bits != "8" && bits != "16")
                throw UsageError{"--bits expects 8 or 16, got " + quote_token(bits)};
            cl.image.bits = bits == "8" ? 8 : 16;
            have_bits = true;
        } else if (arg == "--gamma") {
            const std::string text = take_value();
            const auto gamma = parse_gamma(text);
            if (!gamma)
                throw UsageError{"--gamma expects linear, srgb or a number > 0, got " +
                                 quote_token(text)};
            cl.image.gamma = *gamma;
        } else if (arg == "--no-metadata") {
            flag(cl.metadata, false);
        } else if (arg == "-M" || arg == "--depend") {
            cl.depfile = take_value();
            if (cl.depfile.empty() || cl.depfile == "-") throw UsageError{"-M needs a file name"};
        } else if (arg == "-d" || arg == "--depth") {
            r.max_depth = parse_whole_number("-d", take_value(), 0, kMaxDepthOption);
        } else if (arg == "-w" || arg == "--weight") {
            r.min_weight = parse_nonnegative("-w", take_value());
        } else if (arg == "-m" || arg == "--mode") {
            r.mode = parse_mode(take_value());
        } else if (arg == "-s" || arg == "--samples") {
            r.samples = parse_whole_number("-s", take_value(), 1, kMaxSamplesOption);
            have_samples = true;
        } else if (arg == "-a" || arg == "--adaptive") {
            r.adaptive_threshold = parse_nonnegative("-a", take_value());
        } else if (arg == "-j" || arg == "--threads") {
            r.threads = parse_whole_number("-j", take_value(), 1, kMaxThreadsOption);
        } else if (arg == "--size") {
            cl.size = parse_size(take_value());
        } else if (arg == "--region") {
            cl.region = parse_region(take_value());
        } else if (arg == "--checkpoint") {
            cl.checkpoint = take_value();
            if (cl.checkpoint.empty() || cl.checkpoint == "-")
                throw UsageError{"--checkpoint needs a file name"};
        } else if (arg == "--resume") {
            flag(cl.resume, true);
        } else if (arg == "-r" || arg == "--read-only") {
            flag(cl.read_only, true);
        } else if (arg == "-q" || arg == "--quiet") {
            flag(cl.quiet, true);
        } else if (arg == "--progress") {
            flag(cl.progress, true);
        } else if (arg == "--stats") {
            flag(cl.stats, true);
        } else if (arg == "--no-ambient") {
            flag(r.ambient, false);
        } else if (arg == "--no-diffuse") {
            flag(r.diffuse, false);
        } else if (arg == "--no-specular") {
            flag(r.specular, false);
        } else if (arg == "--no-shadows") {
            flag(r.shadows, false);
        } else if (arg == "--no-reflection") {
            flag(r.reflection, false);
        } else if (arg == "--no-refraction") {
            flag(r.refraction, false);
        } else if (arg == "--no-bvh") {
            flag(r.accelerate, false);
        } else if (arg == "-h" || arg == "--help") {
            flag(cl.help, true);
        } else if (arg == "-V" || arg == "--version") {
            flag(cl.version, true);
        } else {
            options.unknown(usage_text());
        }
    }
    if (!cl.depfile.empty()) {
        if (cl.read_only) throw UsageError{"-M writes a rule for the image, and -r writes none"};
        if (cl.output == "-") throw UsageError{"-M needs -o FILE: the rule's target is the image"};
        if (cl.depfile == cl.output) throw UsageError{"-M and -o name the same file"};
    }
    if (cl.resume && cl.checkpoint.empty())
        throw UsageError{"--resume continues from a checkpoint: give --checkpoint FILE too"};
    if (!cl.checkpoint.empty()) {
        for (const auto& [other, what] :
             {std::pair{cl.output, "-o"}, {cl.depfile, "-M"}, {cl.input, "the scene"}})
            if (cl.checkpoint == other)
                throw UsageError{std::string("--checkpoint and ") + what + " name the same file"};
    }
    if (cl.render.adaptive_threshold && !have_samples) cl.render.samples = kDefaultAdaptiveSamples;
    cl.image.format = format ? *format : format_of_output(cl.output);
    if (cl.image.format == ImageFormat::pfm && cl.region)
        throw UsageError{"--region needs PPM or PNG output: PFM has no place to record the region"};
    if (cl.image.format == ImageFormat::pfm && have_bits)
        throw UsageError{"--bits does not apply to PFM, which always holds 32-bit floats"};
    return cl;
}

std::vector<std::pair<std::string, std::string>> render_identity(const CommandLine& cl, int width,
                                                                 int height,
                                                                 const PixelRect& region) {
    const RenderOptions& r = cl.render;
    std::string switches;
    for (const auto& [on, name] : switch_names(r)) {
        if (on) continue;
        if (!switches.empty()) switches += ' ';
        switches += name;
    }
    return {
        {"version", "rt " RT_VERSION},
        {"size", std::to_string(width) + "x" + std::to_string(height)},
        {"region", std::to_string(region.x0) + "," + std::to_string(region.x1) + "," +
                       std::to_string(region.y0) + "," + std::to_string(region.y1)},
        {"depth", std::to_string(r.max_depth)},
        {"weight", exact_number(r.min_weight)},
        {"mode", mode_name(r.mode)},
        {"samples", std::to_string(r.samples)},
        {"adaptive", r.adaptive_threshold ? exact_number(*r.adaptive_threshold) : "off"},
        {"switches", switches.empty() ? "none" : switches},
    };
}

std::optional<std::string> region_problem(const PixelRect& region, int width, int height) {
    if (PixelRect{0, 0, width, height}.contains(region)) return std::nullopt;
    return "--region " + std::to_string(region.x0) + "," + std::to_string(region.x1) + "," +
           std::to_string(region.y0) + "," + std::to_string(region.y1) + " is outside the " +
           std::to_string(width) + "x" + std::to_string(height) + " image";
}

void add_region_metadata(ImageMetadata& metadata, const PixelRect& region, int width, int height) {
    metadata.set(kRegionKey, std::to_string(region.x0) + "," + std::to_string(region.x1) + "," +
                                 std::to_string(region.y0) + "," + std::to_string(region.y1));
    metadata.set(kFullSizeKey, std::to_string(width) + "x" + std::to_string(height));
}

ImageMetadata image_metadata(const CommandLine& cl) {
    ImageMetadata metadata;
    if (!cl.metadata) return metadata;
    metadata.set("Software", "rt " RT_VERSION);
    // As messages show it: a scene's name with a control character (a line break, say) is
    // recorded escaped, so that every format can hold it.
    metadata.set("Scene", cl.input == "-" ? "<stdin>" : show_token(cl.input, kShowWhole));
    const RenderOptions& r = cl.render;
    std::string options = "-d " + std::to_string(r.max_depth) + " -w " +
                          exact_number(r.min_weight) + " -m " + mode_name(r.mode) + " -s " +
                          std::to_string(r.samples);
    if (r.adaptive_threshold) options += " -a " + exact_number(*r.adaptive_threshold);
    if (cl.size)
        options +=
            " --size " + std::to_string(cl.size->width) + "x" + std::to_string(cl.size->height);
    for (const auto& [on, name] : switch_names(r))
        if (!on) options += std::string(" ") + name;
    // PFM stores the raster's values: bits and gamma do not touch it.
    if (cl.image.format != ImageFormat::pfm)
        options +=
            " --bits " + std::to_string(cl.image.bits) + " --gamma " + gamma_name(cl.image.gamma);
    metadata.set("Options", options);
    return metadata;
}

}  // namespace rt
