// The command-line pieces rtimg's commands share, and writing their images.
#include <algorithm>

#include "common/message_text.h"
#include "common/output_file.h"
#include "rt/error.h"
#include "rt/image_file.h"
#include "rtimg.h"

namespace rtimg {

Arguments parse_arguments(const std::vector<std::string>& args,
                          const std::vector<std::string>& valued,
                          const std::vector<std::string>& flags) {
    Arguments out;
    rt::OptionReader options(args, "o");
    while (options.next()) {
        if (!options.is_option()) {
            out.files.push_back(options.argument());
            continue;
        }
        const std::string arg = options.argument() == "-o" ? "--output" : options.argument();
        const bool takes_value = std::find(valued.begin(), valued.end(), arg) != valued.end();
        if (!takes_value && std::find(flags.begin(), flags.end(), arg) == flags.end())
            options.unknown(usage_text());
        if (takes_value) {
            out.values[arg] = options.value();
        } else {
            options.no_value();
            out.values[arg] = "";
        }
    }
    return out;
}

rt::ImageFormat output_format(const std::string& path) {
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext == ".pgm" || ext == ".PGM") return rt::ImageFormat::ppm;
    if (const auto format = rt::format_from_extension(path)) return *format;
    throw UsageError{"cannot tell the image format of " + rt::quote_token(path, rt::kShowWhole) +
                     " from its extension: name it .ppm, .pgm, .png or .pfm"};
}

bool names_pgm(const std::string& path) {
    const std::string ext = std::filesystem::path(path).extension().string();
    return ext == ".pgm" || ext == ".PGM";
}

// A .pgm name holds grey: an RGB image whose channels agree everywhere becomes one channel;
// one with colour is refused rather than written as colour under a grey name.
rt::SampleImage for_the_name(const std::string& path, rt::SampleImage image) {
    if (!names_pgm(path) || image.channels == 1) return image;
    if (image.channels != 3)
        throw UsageError{rt::quote_token(path, rt::kShowWhole) +
                         " names PGM, which holds grey, and the image has " +
                         std::to_string(image.channels) + " channels: name it .ppm or .png"};
    rt::SampleImage grey = image;
    grey.channels = 1;
    grey.bytes.clear();
    const std::size_t sample_bytes = static_cast<std::size_t>(image.bits / 8);
    for (std::size_t at = 0; at < image.bytes.size(); at += 3 * sample_bytes) {
        for (std::size_t b = 0; b < sample_bytes; ++b)
            if (image.bytes[at + b] != image.bytes[at + sample_bytes + b] ||
                image.bytes[at + b] != image.bytes[at + 2 * sample_bytes + b])
                throw UsageError{rt::quote_token(path, rt::kShowWhole) +
                                 " names PGM, which holds grey, and the image has colour: name "
                                 "it .ppm or .png"};
        grey.bytes.insert(grey.bytes.end(), image.bytes.begin() + static_cast<std::ptrdiff_t>(at),
                          image.bytes.begin() + static_cast<std::ptrdiff_t>(at + sample_bytes));
    }
    return grey;
}

void write_samples(const std::string& path, const rt::SampleImage& colour_image,
                   const rt::ImageMetadata& metadata, bool plain,
                   const std::vector<std::filesystem::path>& inputs) {
    const rt::ImageFormat format = output_format(path);
    const rt::SampleImage image = for_the_name(path, colour_image);
    if (format == rt::ImageFormat::pfm)
        throw UsageError{rt::quote_token(path, rt::kShowWhole) +
                         ": this command writes PPM or PNG, not PFM"};
    std::vector<rt::InputFile> named;
    for (const auto& input : inputs) named.push_back({input, "the input image"});
    rt::OutputFile out(path, named, "the image", "rtimg");
    if (format == rt::ImageFormat::png)
        out.write_bytes(rt::encode_png(image, metadata));
    else
        out.write_bytes(plain ? rt::encode_ppm_plain(image, metadata)
                              : rt::encode_ppm(image, metadata));
}

}  // namespace rtimg
