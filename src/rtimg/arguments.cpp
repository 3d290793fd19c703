// The command-line pieces rtimg's commands share, and writing their images.
#include <algorithm>
#include <charconv>
#include <cmath>

#include "rt/error.h"
#include "rt/image_file.h"
#include "rt/output_file.h"
#include "rtimg.h"

namespace rtimg {

Arguments parse_arguments(const std::vector<std::string>& args,
                          const std::vector<std::string>& valued,
                          const std::vector<std::string>& flags) {
    Arguments out;
    bool options_ended = false;
    for (std::size_t i = 0; i < args.size(); ++i) {
        std::string arg = args[i];
        if (options_ended || arg == "-" || arg.empty() || arg[0] != '-') {
            out.files.push_back(arg);
            continue;
        }
        if (arg == "--") {
            options_ended = true;
            continue;
        }
        if (arg == "-o") arg = "--output";
        std::string value;
        bool inline_value = false;
        if (const auto eq = arg.find('='); eq != std::string::npos && arg.rfind("--", 0) == 0) {
            value = arg.substr(eq + 1);
            arg.resize(eq);
            inline_value = true;
        }
        const bool takes_value = std::find(valued.begin(), valued.end(), arg) != valued.end();
        if (!takes_value && std::find(flags.begin(), flags.end(), arg) == flags.end())
            throw UsageError{"unknown option '" + arg + "'"};
        if (takes_value && !inline_value) {
            if (i + 1 >= args.size()) throw UsageError{arg + " needs a value"};
            value = args[++i];
        } else if (!takes_value && inline_value) {
            throw UsageError{arg + " takes no value"};
        }
        out.values[arg] = value;
    }
    return out;
}

double parse_nonnegative(const std::string& option, const std::string& text) {
    double value = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(value) || value < 0)
        throw UsageError{option + " expects a number >= 0, got '" + text + "'"};
    return value;
}

rt::ImageFormat output_format(const std::string& path) {
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext == ".pgm" || ext == ".PGM") return rt::ImageFormat::ppm;
    if (const auto format = rt::format_from_extension(path)) return *format;
    throw UsageError{"cannot tell the image format of '" + path +
                     "' from its extension: name it .ppm, .pgm, .png or .pfm"};
}

void write_samples(const std::string& path, const rt::SampleImage& image,
                   const rt::ImageMetadata& metadata, bool plain,
                   const std::vector<std::filesystem::path>& inputs) {
    const rt::ImageFormat format = output_format(path);
    if (format == rt::ImageFormat::pfm)
        throw UsageError{"'" + path + "': this command writes PPM or PNG, not PFM"};
    rt::OutputFile out(path, inputs);
    if (format == rt::ImageFormat::png)
        out.write_bytes(rt::encode_png(image, metadata));
    else
        out.write_bytes(plain ? rt::encode_ppm_plain(image, metadata)
                              : rt::encode_ppm(image, metadata));
}

}  // namespace rtimg
