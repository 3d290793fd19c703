// Image files: the formats rt writes (PPM, PNG, PFM), the mapping from the raster's values
// to stored samples, the text that records what made an image, and reading PNG back. A small
// library of its own so that other image tools can share it.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rt/large_pages.h"
#include "rt/raster.h"

namespace rt {

enum class ImageFormat { ppm, png, pfm };

// "ppm", "png", "pfm".
const char* format_name(ImageFormat format);
// The format a name such as "png" stands for (case-insensitive), or nothing.
std::optional<ImageFormat> parse_format_name(std::string_view name);
// The format a file name's extension names (".ppm", ".png", ".pfm", case-insensitive), or
// nothing for any other extension; `has_extension` tells the two cases of nothing apart.
std::optional<ImageFormat> format_from_extension(std::string_view path,
                                                 bool* has_extension = nullptr);

// How a component, once clamped to [0, 1], is encoded before it is quantized: as it is (the
// original's linear output), by the sRGB transfer function, or as c^(1/G).
struct Gamma {
    enum class Kind { linear, srgb, power };
    Kind kind = Kind::linear;
    double exponent = 1;  // G, for Kind::power

    bool operator==(const Gamma&) const = default;
};
// "linear", "srgb" or a number G > 0 (1 is linear); nothing for anything else.
std::optional<Gamma> parse_gamma(std::string_view text);
// The text parse_gamma reads back: "linear", "srgb" or the number.
std::string gamma_name(const Gamma& gamma);
// The encoded value of c in [0, 1].
double encode_gamma(double c, const Gamma& gamma);

// Text records an image carries about itself, in order: "Software" -> "rt 0.1.0" and so on.
// PPM keeps each as a comment line "# Key: value" after the magic number; PNG as a text chunk
// whose keyword is the key.
struct ImageMetadata {
    std::vector<std::pair<std::string, std::string>> entries;

    // The most records a file read may carry (text chunks, or "# Key: value" comments), and
    // the most bytes of text they may hold in all once unpacked: a file beyond either is
    // refused, so that no small file makes reading its metadata slow or large.
    static constexpr std::size_t kMaxEntries = 1024;
    static constexpr std::size_t kMaxBytes = std::size_t{16} << 20;

    // Replaces the key's value, or adds the key at the end.
    void set(std::string_view key, std::string value);
    const std::string* find(std::string_view key) const;
};

// The keys a piece rendered with --region records (rt writes them, rtimg merge reads them):
// "x0,x1,y0,y1", the piece's place, and "WxH", the full image's size.
inline constexpr std::string_view kRegionKey = "Region";
inline constexpr std::string_view kFullSizeKey = "Full-Size";

// Integer samples as PPM and PNG store them: rows from the top, a pixel's channels together,
// each sample big-endian in bits / 8 bytes.
struct SampleImage {
    int width = 0;
    int height = 0;
    int channels = 3;  // 1 grey, 2 grey and alpha, 3 RGB, 4 RGB and alpha
    int bits = 8;      // 8 or 16

    std::vector<std::uint8_t> bytes;

    std::size_t bytes_per_pixel() const { return static_cast<std::size_t>(channels * bits / 8); }
    std::size_t row_bytes() const { return bytes_per_pixel() * static_cast<std::size_t>(width); }
    unsigned max_value() const { return bits == 16 ? 65535u : 255u; }
    unsigned sample(int x, int y, int channel) const {
        const std::size_t i = static_cast<std::size_t>(y) * row_bytes() +
                              static_cast<std::size_t>(x) * bytes_per_pixel() +
                              static_cast<std::size_t>(channel * bits / 8);
        return bits == 16 ? unsigned{bytes[i]} << 8 | bytes[i + 1] : bytes[i];
    }
};

// The raster's red, green and blue as `bits`-bit samples: round(max · encode_gamma(clamp(c,
// 0, 1))), max = 255 or 65535; NaN counts as 0.
SampleImage quantize(const Raster& raster, int bits, const Gamma& gamma);
// Components laid out as a raster's (three per pixel) as the same samples, written at `out`,
// which has room for them (1 or 2 bytes each): quantize and every writer of samples use it.
void quantize_values(std::span<const double> values, int bits, const Gamma& gamma,
                     std::uint8_t* out);
// What quantize rounds with: std::lround's answer for 0 <= x < 2^32 (halves away from zero).
unsigned round_to_nearest(double x);

// The samples a PPM or PNG file of an image stores (SampleImage's layout: red, green and blue,
// rows from the top, each sample big-endian), for a render that keeps only those: 3 or 6
// bytes a pixel where a Raster takes 24. Its memory is not written before the render's
// threads write their rows (2 MiB pages where it is large), so a new one costs no time.
class SampleRaster {
  public:
    // Every sample unset until written. `bits` is 8 or 16 (rt::Error otherwise).
    SampleRaster(int width, int height, int bits, const Gamma& gamma);

    int width() const { return shape_.width; }
    int height() const { return shape_.height; }
    int bits() const { return shape_.bits; }
    const Gamma& gamma() const { return gamma_; }
    // The size, channels and bits, as the headers need them (its bytes are empty).
    const SampleImage& shape() const { return shape_; }
    std::uint8_t* row(int y) {
        return bytes_.data() + static_cast<std::size_t>(y) * shape_.row_bytes();
    }
    std::span<const std::uint8_t> bytes() const { return bytes_; }

  private:
    SampleImage shape_;
    Gamma gamma_;
    std::vector<std::uint8_t, UninitializedAllocator<std::uint8_t>> bytes_;
};

// A raster's samples as a SampleRaster (what quantize gives, in that form).
SampleRaster quantize_raster(const Raster& raster, int bits, const Gamma& gamma);

// Everything that decides an image file's bytes apart from the pixels.
struct ImageEncoding {
    ImageFormat format = ImageFormat::ppm;
    int bits = 8;  // PPM and PNG: 8 or 16
    Gamma gamma;   // PPM and PNG; PFM stores the raster's values as they are
    ImageMetadata metadata;
};

// The whole file. With no metadata, 8 bits and linear gamma, a PPM is exactly what rt has
// always written.
std::string encode_image(const Raster& raster, const ImageEncoding& encoding);
// The same bytes handed to `sink` in order, in pieces: a PPM's header and then runs of rows
// of about 64 KiB each, so that a large image is never held whole a second time; a PNG or
// PFM whole.
void encode_image_in_pieces(const Raster& raster, const ImageEncoding& encoding,
                            const std::function<void(std::string_view)>& sink);

// The file encode_image writes for the raster the samples came from, handed to `sink` as
// encode_image_in_pieces hands it: the PPM's samples straight from `samples`, no copy. The
// format must be PPM or PNG, and the bits and gamma the samples'
// (std::invalid_argument otherwise).
void encode_samples_in_pieces(const SampleRaster& samples, const ImageEncoding& encoding,
                              const std::function<void(std::string_view)>& sink);

// Binary PPM: P6 for three channels, P5 for one; maxval 255 or 65535.
std::string encode_ppm(const SampleImage& image, const ImageMetadata& metadata);
// The header encode_ppm writes before the samples (image.bytes is not read).
std::string ppm_header(const SampleImage& image, const ImageMetadata& metadata);
// PNG of any channel count and 8 or 16 bits, each row with the filter that makes its bytes
// smallest in absolute value (the usual heuristic), compressed by rt's deflate.
std::string encode_png(const SampleImage& image, const ImageMetadata& metadata);
// The same for samples held elsewhere: `shape`'s size, channels and bits (its bytes unread),
// `samples` as its bytes would be.
std::string encode_png(const SampleImage& shape, const std::uint8_t* samples,
                       const ImageMetadata& metadata);
// PFM ("PF", RGB): 32-bit floats as the raster holds them, little-endian (scale -1.0), rows
// from the bottom as the format has them. PFM has no place for metadata.
std::string encode_pfm(const Raster& raster);

// A PNG file read back: any standard bit depth and colour type, interlaced or not. Bit depths
// below 8 and palettes become 8-bit samples (a palette becomes RGB, or RGB and alpha when it
// has transparency); 16-bit samples stay 16-bit. Text chunks (tEXt, zTXt, iTXt) become the
// metadata. Throws rt::Error for anything malformed, with the reason.
struct DecodedImage {
    SampleImage image;
    ImageMetadata metadata;
};
DecodedImage decode_png(std::string_view file);

}  // namespace rt
