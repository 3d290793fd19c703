// What the image formats share: their names, the value mapping and the metadata.
#include "rt/image_io.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <span>
#include <stdexcept>

#include "rt/error.h"

namespace rt {

namespace {

bool equal_ignoring_case(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const auto lower = [](char c) {
            return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c;
        };
        if (lower(a[i]) != lower(b[i])) return false;
    }
    return true;
}

}  // namespace

const char* format_name(ImageFormat format) {
    switch (format) {
        case ImageFormat::ppm:
            return "ppm";
        case ImageFormat::png:
            return "png";
        case ImageFormat::pfm:
            return "pfm";
    }
    return "?";
}

std::optional<ImageFormat> parse_format_name(std::string_view name) {
    for (const ImageFormat f : {ImageFormat::ppm, ImageFormat::png, ImageFormat::pfm})
        if (equal_ignoring_case(name, format_name(f))) return f;
    return std::nullopt;
}

std::optional<ImageFormat> format_from_extension(std::string_view path, bool* has_extension) {
    const std::string extension = std::filesystem::path(path).extension().string();
    if (has_extension) *has_extension = !extension.empty();
    if (extension.size() < 2) return std::nullopt;
    return parse_format_name(std::string_view(extension).substr(1));
}

std::optional<Gamma> parse_gamma(std::string_view text) {
    if (equal_ignoring_case(text, "linear")) return Gamma{};
    if (equal_ignoring_case(text, "srgb")) return Gamma{Gamma::Kind::srgb, 1};
    double g = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, g);
    if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(g) || !(g > 0))
        return std::nullopt;
    if (g == 1) return Gamma{};
    return Gamma{Gamma::Kind::power, g};
}

std::string gamma_name(const Gamma& gamma) {
    switch (gamma.kind) {
        case Gamma::Kind::linear:
            return "linear";
        case Gamma::Kind::srgb:
            return "srgb";
        case Gamma::Kind::power:
            break;
    }
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, gamma.exponent);
    return std::string(buffer, result.ptr);
}

double encode_gamma(double c, const Gamma& gamma) {
    switch (gamma.kind) {
        case Gamma::Kind::linear:
            return c;
        case Gamma::Kind::srgb:
            // IEC 61966-2-1: a straight segment near black, then a 1/2.4 power.
            return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
        case Gamma::Kind::power:
            return std::pow(c, 1 / gamma.exponent);
    }
    return c;
}

void ImageMetadata::set(std::string_view key, std::string value) {
    for (auto& [k, v] : entries)
        if (k == key) {
            v = std::move(value);
            return;
        }
    entries.emplace_back(std::string(key), std::move(value));
}

const std::string* ImageMetadata::find(std::string_view key) const {
    for (const auto& [k, v] : entries)
        if (k == key) return &v;
    return nullptr;
}

// Without the library call (three million at 1024 x 1024, on one thread after the render's
// several): x minus its whole part is exact, so the comparison with a half is too.
unsigned round_to_nearest(double x) {
    auto whole = static_cast<unsigned>(x);
    if (x - whole >= 0.5) ++whole;
    return whole;
}

namespace {

void require_sample_bits(int bits) {
    if (bits != 8 && bits != 16) throw Error("images have 8 or 16 bits per sample");
}

}  // namespace

SampleImage quantize(const Raster& raster, int bits, const Gamma& gamma) {
    require_sample_bits(bits);
    SampleImage image;
    image.width = raster.width();
    image.height = raster.height();
    image.channels = 3;
    image.bits = bits;
    image.bytes.resize(image.row_bytes() * static_cast<std::size_t>(image.height));
    quantize_values(raster.values(), bits, gamma, image.bytes.data());
    return image;
}

SampleRaster::SampleRaster(int width, int height, int bits, const Gamma& gamma)
    : shape_{width, height, 3, bits, {}}, gamma_(gamma) {
    require_sample_bits(bits);
    bytes_.resize(shape_.row_bytes() * static_cast<std::size_t>(height));
}

SampleRaster quantize_raster(const Raster& raster, int bits, const Gamma& gamma) {
    SampleRaster samples(raster.width(), raster.height(), bits, gamma);
    if (raster.height() > 0) quantize_values(raster.values(), bits, gamma, samples.row(0));
    return samples;
}

namespace {

template <int bits>
void store_sample(std::uint8_t* out, std::size_t i, std::uint32_t v) {
    if constexpr (bits == 16) {
        out[2 * i] = static_cast<std::uint8_t>(v >> 8);
        out[2 * i + 1] = static_cast<std::uint8_t>(v);
    } else {
        out[i] = static_cast<std::uint8_t>(v);
    }
}

// A component clamped to [0, 1], NaN to 0: what every gamma encodes.
double clamped(double c) {
    if (!(c > 0)) return 0;  // also NaN
    return c > 1 ? 1 : c;
}

// One linear component, scaled and rounded half away from zero.
std::uint32_t linear_sample(double c, double max) { return round_to_nearest(max * clamped(c)); }

// Linear samples, the default, four components at a time in the compiler's vectors (which
// its own vectoriser does not do here: the clamps stay branches). The same clamps and
// rounding as linear_sample, so the same samples; a 1024 x 1024 image in about 2 ms
// instead of 8 on one thread.
template <int bits>
void quantize_linear(std::span<const double> values, std::uint8_t* out) {
    using Doubles = double __attribute__((vector_size(32)));
    using Ints = std::int32_t __attribute__((vector_size(16)));
    constexpr double max = bits == 16 ? 65535 : 255;
    std::size_t i = 0;
    for (; i + 4 <= values.size(); i += 4) {
        Doubles c;
        std::memcpy(&c, values.data() + i, sizeof c);
        const Doubles zero{}, one = zero + 1;
        c = c > zero ? c : zero;  // NaN fails the comparison: 0
        c = c < one ? c : one;
        const Doubles x = max * c;
        const Ints whole = __builtin_convertvector(x, Ints);  // truncated, as x >= 0
        // x minus its whole part is exact, and so is twice that, which is below 2: its whole
        // part is 1 exactly where the rest is a half or more. (A comparison's mask, converted
        // to 32-bit lanes, took the compiler's scalar code.)
        const Doubles rest = x - __builtin_convertvector(whole, Doubles);
        const Ints v = whole + __builtin_convertvector(rest + rest, Ints);
        for (std::size_t k = 0; k < 4; ++k)
            store_sample<bits>(out, i + k, static_cast<std::uint32_t>(v[k]));
    }
    for (; i < values.size(); ++i) store_sample<bits>(out, i, linear_sample(values[i], max));
}

}  // namespace

void quantize_values(std::span<const double> values, int bits, const Gamma& gamma,
                     std::uint8_t* out) {
    require_sample_bits(bits);
    if (gamma.kind == Gamma::Kind::linear)
        return bits == 16 ? quantize_linear<16>(values, out) : quantize_linear<8>(values, out);
    const double max = bits == 16 ? 65535 : 255;
    for (const double c : values) {
        const unsigned v = round_to_nearest(max * encode_gamma(clamped(c), gamma));
        if (bits == 16) *out++ = static_cast<std::uint8_t>(v >> 8);
        *out++ = static_cast<std::uint8_t>(v);
    }
}

std::string encode_image(const Raster& raster, const ImageEncoding& encoding) {
    switch (encoding.format) {
        case ImageFormat::ppm: {
            std::string out;
            encode_image_in_pieces(raster, encoding, [&](std::string_view piece) { out += piece; });
            return out;
        }
        case ImageFormat::png:
            return encode_png(quantize(raster, encoding.bits, encoding.gamma), encoding.metadata);
        case ImageFormat::pfm:
            return encode_pfm(raster);
    }
    throw Error("unknown image format");
}

namespace {

// A PPM's samples are handed on about this much at a time: written in pieces of this size, a
// 1024 x 1024 image's 3 MiB took 2.4 ms of write calls against 10.5 ms as one.
constexpr std::size_t kPieceBytes = std::size_t{64} << 10;

}  // namespace

void encode_image_in_pieces(const Raster& raster, const ImageEncoding& encoding,
                            const std::function<void(std::string_view)>& sink) {
    if (encoding.format != ImageFormat::ppm) return sink(encode_image(raster, encoding));
    // The samples quantized a run of rows at a time into one buffer, which stays in the cache
    // and is handed on from there: no 3 MiB of fresh pages for a 1024 x 1024 image.
    require_sample_bits(encoding.bits);
    const SampleImage shape{raster.width(), raster.height(), 3, encoding.bits, {}};
    std::string piece = ppm_header(shape, encoding.metadata);
    const std::size_t row = shape.row_bytes();
    const std::size_t row_values = static_cast<std::size_t>(raster.width()) * 3;
    const int rows =
        static_cast<int>(std::max<std::size_t>(1, kPieceBytes / std::max<std::size_t>(row, 1)));
    for (int y = 0; y < shape.height; y += rows) {
        const int end = std::min(shape.height, y + rows);
        const std::size_t start = piece.size();
        piece.resize(start + row * static_cast<std::size_t>(end - y));
        quantize_values(raster.values().subspan(static_cast<std::size_t>(y) * row_values,
                                                static_cast<std::size_t>(end - y) * row_values),
                        shape.bits, encoding.gamma,
                        reinterpret_cast<std::uint8_t*>(piece.data() + start));
        sink(piece);
        piece.clear();
    }
    if (!piece.empty()) sink(piece);  // an image of no rows: the header alone
}

void encode_samples_in_pieces(const SampleRaster& samples, const ImageEncoding& encoding,
                              const std::function<void(std::string_view)>& sink) {
    if (encoding.format == ImageFormat::pfm)
        throw std::invalid_argument("encode_samples_in_pieces: PFM stores floats, not samples");
    if (encoding.bits != samples.bits() || !(encoding.gamma == samples.gamma()))
        throw std::invalid_argument(
            "encode_samples_in_pieces: the samples were quantized with other bits or gamma");
    const auto bytes = samples.bytes();
    if (encoding.format == ImageFormat::png)
        return sink(encode_png(samples.shape(), bytes.data(), encoding.metadata));
    sink(ppm_header(samples.shape(), encoding.metadata));
    for (std::size_t at = 0; at < bytes.size(); at += kPieceBytes)
        sink(std::string_view(reinterpret_cast<const char*>(bytes.data()) + at,
                              std::min(kPieceBytes, bytes.size() - at)));
}

}  // namespace rt
