// Image files read back whatever their format (PPM P2/P3/P5/P6, PNG, PFM): for the tools that
// compare, merge and convert images (rtimg and the golden-image test) and for textures.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "rt/image_io.h"

namespace rt {

struct ImageFile {
    ImageFormat format = ImageFormat::ppm;
    std::string variant;        // how the format stores it: "P6", "P3", "PNG", "PF"...
    SampleImage samples;        // PPM and PNG: the samples as stored (PFM: size only, no bytes)
    std::vector<float> floats;  // PFM: red, green, blue per pixel, rows from the top
    ImageMetadata metadata;
    unsigned maxval = 0;  // a PPM decoded with PpmSamples::as_stored: the file's maximum value

    // The value of a full-intensity sample: samples.max_value() (255 or 65535), or the
    // file's own maximum value for a PPM whose samples were kept as stored.
    unsigned full_sample() const { return maxval != 0 ? maxval : samples.max_value(); }
    int width() const { return samples.width; }
    int height() const { return samples.height; }
    // 1 grey, 2 grey and alpha, 3 RGB, 4 RGBA; PFM is 3.
    int channels() const { return samples.channels; }
    // Bits per sample: 8 or 16, or 32 for PFM's floats.
    int bits() const { return format == ImageFormat::pfm ? 32 : samples.bits; }
    // Channel c of pixel (x, y) scaled so that 1 is full intensity (PFM's value as it is).
    double value(int x, int y, int c) const;
    // Red, green or blue (c = 0, 1, 2) in 8-bit levels (255 is full intensity): grey stands
    // for all three; alpha is not colour and is left out.
    double level(int x, int y, int c) const;
};

// How a PPM's samples are kept when its maximum value is neither 255 nor 65535: rescaled to 8
// or 16 bits, as the tools compare, merge and convert them, or as the file has them (in 8 bits
// up to 255, else 16), so that a texture divides each by the file's own maximum exactly.
enum class PpmSamples { rescaled, as_stored };

// Reads a file, telling the format from its first bytes; throws rt::Error with the reason.
ImageFile read_image_file(const std::filesystem::path& path);
ImageFile decode_image(std::string_view file, PpmSamples ppm = PpmSamples::rescaled);

// PPM and PGM, binary (P6, P5) or plain text (P3, P2), any maxval up to 65535. Comment lines
// "# Key: value" in the header become the metadata, as encode_ppm writes them. A header that
// claims more samples than the file holds is refused before they are allocated.
ImageFile decode_ppm(std::string_view file, PpmSamples samples = PpmSamples::rescaled);
// PFM colour ("PF") or grey ("Pf", which becomes RGB), either byte order.
ImageFile decode_pfm(std::string_view file);

// Whether a metadata key can be a PPM comment's ("# Key: value"): not empty, and no spaces
// or control characters, so that it reads back as it was written and ends no line.
bool ppm_key(std::string_view key);

// Plain-text PPM (P3) or PGM (P2), with the metadata as comments like encode_ppm's.
std::string encode_ppm_plain(const SampleImage& image, const ImageMetadata& metadata);

// The image's colour as a raster (values scaled so 1 is full intensity): for convert.
Raster to_raster(const ImageFile& image);

}  // namespace rt
