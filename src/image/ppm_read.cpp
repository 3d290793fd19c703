// PPM and PGM input, binary and plain, keeping rt's "# Key: value" comments as metadata: the
// one PPM reader, for the image tools and for textures (src/scene/texture.cpp).
#include <charconv>

#include "common/ascii.h"
#include "rt/error.h"
#include "rt/image_file.h"
#include "rt/limits.h"

namespace rt {

namespace {

// Walks the header and plain-text samples: numbers between whitespace and comments.
class Cursor {
  public:
    Cursor(std::string_view file, ImageMetadata* metadata) : s_(file), metadata_(metadata) {}

    // A decimal number of at most 10^9 (so that width times height cannot overflow).
    unsigned long number(const char* what) {
        skip_space_and_comments();
        const char* start = s_.data() + at_;
        unsigned long value = 0;
        const auto [ptr, ec] = std::from_chars(start, s_.data() + s_.size(), value);
        if (ptr == start) throw Error(std::string("expected ") + what + " in the PPM file");
        if (ec != std::errc() || value > 1'000'000'000)
            throw Error(std::string(what) + " too large in the PPM file");
        at_ = static_cast<std::size_t>(ptr - s_.data());
        return value;
    }
    // After maxval: exactly one whitespace character, then the binary samples.
    std::string_view binary_rest() {
        if (at_ >= s_.size() || !is_ascii_space(s_[at_]))
            throw Error("expected one whitespace character after the PPM maximum value");
        return s_.substr(at_ + 1);
    }
    // The bytes not read yet.
    std::size_t remaining() const { return s_.size() - at_; }

  private:
    void skip_space_and_comments() {
        while (at_ < s_.size()) {
            if (is_ascii_space(s_[at_])) {
                ++at_;
            } else if (s_[at_] == '#') {
                std::size_t end = s_.find('\n', at_);
                if (end == std::string_view::npos) end = s_.size();
                if (metadata_ != nullptr) keep_comment(s_.substr(at_ + 1, end - at_ - 1));
                at_ = end;
            } else {
                break;
            }
        }
    }
    // "# Key: value", as encode_ppm writes; other comments are not metadata. A key has no
    // spaces or control characters, which encode_ppm refuses to write.
    void keep_comment(std::string_view text) {
        if (!text.empty() && text[0] == ' ') text.remove_prefix(1);
        if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
        const std::size_t colon = text.find(": ");
        if (colon == std::string_view::npos || colon == 0 || !ppm_key(text.substr(0, colon)))
            return;
        if (++entries_ > ImageMetadata::kMaxEntries)
            throw Error("PPM header has more than " + std::to_string(ImageMetadata::kMaxEntries) +
                        " metadata comments");
        metadata_->set(text.substr(0, colon), std::string(text.substr(colon + 2)));
    }

    std::string_view s_;
    ImageMetadata* metadata_;
    std::size_t at_ = 2;  // after the magic number
    std::size_t entries_ = 0;
};

}  // namespace

ImageFile decode_ppm(std::string_view file, PpmSamples samples) {
    if (file.size() < 3 || file[0] != 'P' ||
        std::string_view("2356").find(file[1]) == std::string_view::npos ||
        !is_ascii_space(file[2]))
        throw Error("not a PPM or PGM file (expected P6, P5, P3 or P2)");
    ImageFile image;
    image.format = ImageFormat::ppm;
    image.variant = std::string(file.substr(0, 2));
    const bool plain = file[1] == '2' || file[1] == '3';
    Cursor cursor(file, &image.metadata);
    const unsigned long width = cursor.number("width");
    const unsigned long height = cursor.number("height");
    const unsigned long maxval = cursor.number("maximum value");
    if (width < 1 || height < 1) throw Error("PPM image has no pixels");
    if (width * height > static_cast<unsigned long>(kMaxImagePixels))
        throw Error("PPM image " + std::to_string(width) + "x" + std::to_string(height) +
                    " is larger than " + std::to_string(kMaxImagePixels) + " pixels");
    if (maxval < 1 || maxval > 65535) throw Error("PPM maximum value must be 1 to 65535");
    SampleImage& out = image.samples;
    out.width = static_cast<int>(width);
    out.height = static_cast<int>(height);
    out.channels = file[1] == '3' || file[1] == '6' ? 3 : 1;
    out.bits = maxval > 255 ? 16 : 8;
    const bool rescale = samples == PpmSamples::rescaled;
    if (!rescale) image.maxval = static_cast<unsigned>(maxval);
    const std::size_t count = width * height * static_cast<std::size_t>(out.channels);
    const std::size_t stored_bytes = maxval > 255 ? 2 : 1;
    std::string_view binary;
    if (!plain) {
        binary = cursor.binary_rest();
        if (binary.size() < count * stored_bytes) throw Error("PPM pixel data ends early");
    } else if (cursor.remaining() < count) {
        throw Error("PPM pixel data ends early");  // each plain sample takes a byte at least
    }
    out.bytes.resize(count * (out.bits / 8));
    const unsigned long max = out.max_value();
    for (std::size_t i = 0; i < count; ++i) {
        unsigned long v = 0;
        if (plain)
            v = cursor.number("pixel value");
        else
            v = stored_bytes == 2
                    ? static_cast<unsigned long>(static_cast<unsigned char>(binary[2 * i])) << 8 |
                          static_cast<unsigned char>(binary[2 * i + 1])
                    : static_cast<unsigned char>(binary[i]);
        if (v > maxval) throw Error("PPM pixel value above the maximum value");
        if (rescale && maxval != max) v = (v * max + maxval / 2) / maxval;  // rounded
        if (out.bits == 16) {
            out.bytes[2 * i] = static_cast<std::uint8_t>(v >> 8);
            out.bytes[2 * i + 1] = static_cast<std::uint8_t>(v);
        } else {
            out.bytes[i] = static_cast<std::uint8_t>(v);
        }
    }
    return image;
}

std::string encode_ppm_plain(const SampleImage& image, const ImageMetadata& metadata) {
    if (image.channels != 3 && image.channels != 1)
        throw Error("PPM stores RGB or grey images, not " + std::to_string(image.channels) +
                    " channels");
    // The binary header with the magic number changed; then the samples as text lines.
    std::string out = encode_ppm(
        SampleImage{image.width, image.height, image.channels, image.bits, {}}, metadata);
    out[1] = image.channels == 3 ? '3' : '2';
    // Lines of at most 70 characters, as the format asks.
    std::size_t line = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < image.channels; ++c) {
                const std::string text = std::to_string(image.sample(x, y, c));
                if (line != 0 && line + 1 + text.size() > 70) {
                    out += '\n';
                    line = 0;
                } else if (line != 0) {
                    out += ' ';
                    ++line;
                }
                out += text;
                line += text.size();
            }
    out += '\n';
    return out;
}

}  // namespace rt
