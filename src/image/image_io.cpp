// What the image formats share: their names, the value mapping and the metadata.
#include "rt/image_io.h"

#include <charconv>
#include <cmath>
#include <filesystem>

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
    quantize_into(raster, bits, gamma, image.bytes.data());
    return image;
}

void quantize_into(const Raster& raster, int bits, const Gamma& gamma, std::uint8_t* out) {
    require_sample_bits(bits);
    const double max = bits == 16 ? 65535 : 255;
    for (int y = 0; y < raster.height(); ++y)
        for (int x = 0; x < raster.width(); ++x) {
            const Spectrum s = raster.at(x, y);
            for (std::size_t i = 0; i < 3; ++i) {
                double c = s[i];
                if (!(c > 0)) c = 0;  // also NaN
                if (c > 1) c = 1;
                const unsigned v = round_to_nearest(max * encode_gamma(c, gamma));
                if (bits == 16) *out++ = static_cast<std::uint8_t>(v >> 8);
                *out++ = static_cast<std::uint8_t>(v);
            }
        }
}

std::string encode_image(const Raster& raster, const ImageEncoding& encoding) {
    switch (encoding.format) {
        case ImageFormat::ppm: {
            // The samples quantized straight into the file's bytes: no image of its own to
            // fill and then copy (3 MiB of fresh pages each at 1024 x 1024).
            require_sample_bits(encoding.bits);
            const SampleImage shape{raster.width(), raster.height(), 3, encoding.bits, {}};
            std::string out = ppm_header(shape, encoding.metadata);
            const std::size_t header = out.size();
            out.resize(header + shape.row_bytes() * static_cast<std::size_t>(shape.height));
            quantize_into(raster, shape.bits, encoding.gamma,
                          reinterpret_cast<std::uint8_t*>(out.data() + header));
            return out;
        }
        case ImageFormat::png:
            return encode_png(quantize(raster, encoding.bits, encoding.gamma), encoding.metadata);
        case ImageFormat::pfm:
            return encode_pfm(raster);
    }
    throw Error("unknown image format");
}

}  // namespace rt
