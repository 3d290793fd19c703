// rtimg convert IN OUT: another format, bit depth or gamma; the metadata comes along.
#include <sstream>
#include <string>

#include "common/message_text.h"
#include "common/output_file.h"
#include "rt/image_file.h"
#include "rtimg.h"

namespace rtimg {

namespace {

// The Options record says how the samples were written; converting changes that, so its
// --bits and --gamma become the output's (and go, for PFM, which has neither).
void describe_encoding(rt::ImageMetadata& metadata, const rt::ImageEncoding& encoding) {
    const std::string* options = metadata.find("Options");
    if (options == nullptr) return;
    std::istringstream words(*options);
    std::string kept, word;
    while (words >> word) {
        if (word == "--bits" || word == "--gamma") {
            words >> word;  // and its value
            continue;
        }
        kept += (kept.empty() ? "" : " ") + word;
    }
    if (encoding.format != rt::ImageFormat::pfm)
        kept += " --bits " + std::to_string(encoding.bits) + " --gamma " +
                rt::gamma_name(encoding.gamma);
    metadata.set("Options", kept);
}

}  // namespace

int convert(const std::vector<std::string>& args) {
    const Arguments a = parse_arguments(args, {"--bits", "--gamma"}, {"--plain"});
    if (a.files.size() != 2) throw UsageError{"convert needs two files: rtimg convert IN OUT"};
    rt::ImageEncoding encoding;
    encoding.format = output_format(a.files[1]);
    std::optional<rt::Gamma> gamma = rt::Gamma{};
    if (a.has("--gamma")) {
        gamma = rt::parse_gamma(a.values.at("--gamma"));
        if (!gamma)
            throw UsageError{"--gamma expects linear, srgb or a number > 0, got " +
                             rt::quote_token(a.values.at("--gamma"))};
    }
    encoding.gamma = *gamma;
    if (a.has("--bits")) {
        const std::string& bits = a.values.at("--bits");
        if (bits != "8" && bits != "16")
            throw UsageError{"--bits expects 8 or 16, got " + rt::quote_token(bits)};
        if (encoding.format == rt::ImageFormat::pfm)
            throw UsageError{"--bits does not apply to PFM, which always holds 32-bit floats"};
        encoding.bits = bits == "8" ? 8 : 16;
    }
    const bool plain = a.has("--plain");
    if (plain && encoding.format != rt::ImageFormat::ppm)
        throw UsageError{"--plain applies to PPM output only"};

    const rt::ImageFile in = rt::read_image_file(a.files[0]);
    if (!a.has("--bits") && in.format != rt::ImageFormat::pfm) encoding.bits = in.bits();
    encoding.metadata = in.metadata;
    describe_encoding(encoding.metadata, encoding);
    const rt::Raster raster = rt::to_raster(in);
    // A .pgm name: grey samples, or a refusal before anything is written.
    const bool pgm = names_pgm(a.files[1]);
    const rt::SampleImage samples =
        pgm || plain ? for_the_name(a.files[1], rt::quantize(raster, encoding.bits, encoding.gamma))
                     : rt::SampleImage{};
    rt::OutputFile out(a.files[1], {{a.files[0], "the input image"}}, "the image", "rtimg");
    if (plain)
        out.write_bytes(rt::encode_ppm_plain(samples, encoding.metadata));
    else if (pgm)
        out.write_bytes(rt::encode_ppm(samples, encoding.metadata));
    else
        out.write_bytes(rt::encode_image(raster, encoding));
    return kExitOk;
}

}  // namespace rtimg
