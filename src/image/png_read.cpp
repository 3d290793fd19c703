// PNG input: every standard colour type and bit depth, Adam7 interlacing, text chunks.
#include <array>
#include <vector>

#include "common/message_text.h"
#include "image/deflate.h"
#include "png_format.h"
#include "rt/error.h"
#include "rt/image_io.h"
#include "rt/limits.h"

namespace rt {

namespace {

using namespace png_format;

std::uint32_t get_u32(std::string_view s, std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = v << 8 | static_cast<unsigned char>(s[at + i]);
    return v;
}

// A chunk type as messages show it: its four bytes, any that are not printable escaped.
std::string shown(std::string_view type) { return show_token(type, kShowWhole); }

// tEXt and zTXt hold Latin-1, as does every keyword; metadata is UTF-8.
std::string latin1_to_utf8(std::string_view text) {
    std::string out;
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if (c < 128) {
            out.push_back(ch);
        } else {
            out.push_back(static_cast<char>(0xC0 | c >> 6));
            out.push_back(static_cast<char>(0x80 | (c & 0x3F)));
        }
    }
    return out;
}

// What the text chunks read so far have taken of the metadata's bounds.
struct TextBudget {
    std::size_t entries = 0;
    std::size_t bytes = 0;
};

// Splits "keyword\0rest", the keyword as the specification allows it; throws otherwise.
std::pair<std::string_view, std::string_view> split_keyword(std::string_view body,
                                                            std::string_view type) {
    const std::size_t nul = body.find('\0');
    if (nul == std::string_view::npos)
        throw Error("PNG " + shown(type) + " chunk has no keyword ending in a NUL");
    const std::string_view keyword = body.substr(0, nul);
    if (!valid_keyword(keyword))
        throw Error("PNG " + shown(type) + " chunk has an invalid keyword " +
                    quote_token(keyword, 80) +
                    " (1 to 79 printable Latin-1 characters, no leading, trailing or double "
                    "spaces)");
    return {keyword, body.substr(nul + 1)};
}

void read_text_chunk(std::string_view type, std::string_view body, ImageMetadata& metadata,
                     TextBudget& budget) {
    if (++budget.entries > ImageMetadata::kMaxEntries)
        throw Error("PNG file has more than " + std::to_string(ImageMetadata::kMaxEntries) +
                    " text chunks");
    // Plain names rather than a structured binding, which clang 14's lambdas cannot capture.
    const auto split = split_keyword(body, type);
    const std::string_view keyword = split.first, rest = split.second;
    // What is left of the bound on all text: a compressed chunk may unpack to no more.
    const std::size_t room = ImageMetadata::kMaxBytes - budget.bytes;
    // A chunk that would unpack past what is left is refused with the bound in all named.
    const auto unpack = [&](std::string_view data) {
        try {
            return zlib_decompress(data, room);
        } catch (const Error& e) {
            throw Error("PNG " + shown(type) + " chunk " + quote_token(keyword, 80) + ": " +
                        e.what() + "; the text chunks may hold " +
                        std::to_string(ImageMetadata::kMaxBytes) + " bytes in all");
        }
    };
    std::string text;
    if (type == "tEXt") {
        text = latin1_to_utf8(rest);
    } else if (type == "zTXt") {
        if (rest.empty() || rest[0] != 0) throw Error("PNG zTXt chunk has an unknown compression");
        text = latin1_to_utf8(unpack(rest.substr(1)));
    } else {  // iTXt: flag, method, language tag, translated keyword, text
        if (rest.size() < 2) throw Error("PNG iTXt chunk is too short");
        const bool compressed = rest[0] != 0;
        std::string_view tail = rest.substr(2);
        for (int skip = 0; skip < 2; ++skip) {
            const std::size_t nul = tail.find('\0');
            if (nul == std::string_view::npos) throw Error("PNG iTXt chunk is malformed");
            tail = tail.substr(nul + 1);
        }
        text = compressed ? unpack(tail) : std::string(tail);
    }
    // A NUL cannot be written back (it would end the text), so it is refused, not dropped.
    if (text.find('\0') != std::string::npos)
        throw Error("PNG " + shown(type) + " chunk " + quote_token(keyword, 80) +
                    " has a NUL character in its text");
    std::string key = latin1_to_utf8(keyword);
    budget.bytes += key.size();
    if (text.size() > ImageMetadata::kMaxBytes - budget.bytes)
        throw Error("PNG file's text chunks hold more than " +
                    std::to_string(ImageMetadata::kMaxBytes) + " bytes in all");
    budget.bytes += text.size();
    metadata.set(key, std::move(text));
}

struct Header {
    int width = 0;
    int height = 0;
    int depth = 0;
    int colour = 0;
    bool interlaced = false;
    int channels() const {
        return colour == kRgb ? 3 : colour == kGreyAlpha ? 2 : colour == kRgbAlpha ? 4 : 1;
    }
    int bits_per_pixel() const { return channels() * depth; }
    std::size_t row_bytes(int w) const {
        return (static_cast<std::size_t>(w) * static_cast<std::size_t>(bits_per_pixel()) + 7) / 8;
    }
};

Header read_header(std::string_view body) {
    if (body.size() != 13) throw Error("PNG IHDR chunk has the wrong length");
    const std::uint32_t width = get_u32(body, 0);
    const std::uint32_t height = get_u32(body, 4);
    Header h;
    h.depth = static_cast<unsigned char>(body[8]);
    h.colour = static_cast<unsigned char>(body[9]);
    if (width == 0 || height == 0) throw Error("PNG image has no pixels");
    if (width > 0x7FFFFFFFu || height > 0x7FFFFFFFu ||
        std::uint64_t{width} * height > static_cast<std::uint64_t>(kMaxImagePixels))
        throw Error("PNG image " + std::to_string(width) + "x" + std::to_string(height) +
                    " is larger than " + std::to_string(kMaxImagePixels) + " pixels");
    h.width = static_cast<int>(width);
    h.height = static_cast<int>(height);
    const int d = h.depth;
    const bool low = d == 1 || d == 2 || d == 4;
    const bool valid = (h.colour == kGrey && (low || d == 8 || d == 16)) ||
                       (h.colour == kPalette && (low || d == 8)) ||
                       ((h.colour == kRgb || h.colour == kGreyAlpha || h.colour == kRgbAlpha) &&
                        (d == 8 || d == 16));
    if (!valid)
        throw Error("PNG has an invalid bit depth " + std::to_string(d) + " for colour type " +
                    std::to_string(h.colour));
    if (body[10] != 0 || body[11] != 0) throw Error("PNG uses an unknown compression or filter");
    if (body[12] != 0 && body[12] != 1) throw Error("PNG uses an unknown interlace method");
    h.interlaced = body[12] == 1;
    return h;
}

// A pass of the image: Adam7's seven, or the whole image as one.
struct Pass {
    int x0, y0, dx, dy;
    int width(const Header& h) const { return h.width > x0 ? (h.width - x0 + dx - 1) / dx : 0; }
    int height(const Header& h) const { return h.height > y0 ? (h.height - y0 + dy - 1) / dy : 0; }
};

std::vector<Pass> passes(const Header& h) {
    if (!h.interlaced) return {{0, 0, 1, 1}};
    return {{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4},
            {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}};
}

// Undoes the row filters of one pass in place; `data` starts at its first filter byte.
void unfilter(std::uint8_t* data, std::size_t row, int rows, std::size_t bpp) {
    const std::uint8_t* up = nullptr;
    for (int y = 0; y < rows; ++y) {
        const int type = data[0];
        if (type >= kFilterTypes) throw Error("PNG row has an unknown filter type");
        std::uint8_t* cur = data + 1;
        for (std::size_t i = 0; i < row; ++i) {
            const std::uint8_t a = i >= bpp ? cur[i - bpp] : 0;
            const std::uint8_t b = up ? up[i] : 0;
            const std::uint8_t c = up && i >= bpp ? up[i - bpp] : 0;
            cur[i] = static_cast<std::uint8_t>(cur[i] + predict(type, a, b, c));
        }
        up = cur;
        data += row + 1;
    }
}

}  // namespace

DecodedImage decode_png(std::string_view file) {
    if (file.substr(0, kSignature.size()) != kSignature) throw Error("not a PNG file");
    DecodedImage result;
    Header h;
    bool have_header = false;
    bool have_end = false;
    std::string_view palette;
    std::string_view transparency;
    std::string compressed;
    TextBudget text_budget;
    for (std::size_t at = kSignature.size(); !have_end;) {
        if (file.size() - at < 12) throw Error("PNG file ends before its IEND chunk");
        const std::uint32_t length = get_u32(file, at);
        const std::string_view type = file.substr(at + 4, 4);
        if (length > 0x7FFFFFFFu || file.size() - at - 12 < length)
            throw Error("PNG " + shown(type) + " chunk runs past the end of the file");
        const std::string_view body = file.substr(at + 8, length);
        if (get_u32(file, at + 8 + length) != crc32(body, crc32(type)))
            throw Error("PNG " + shown(type) + " chunk has a wrong CRC");
        at += 12 + length;
        if (!have_header && type != "IHDR") throw Error("PNG file does not start with IHDR");
        if (type == "IHDR") {
            if (have_header) throw Error("PNG file has two IHDR chunks");
            h = read_header(body);
            have_header = true;
        } else if (type == "PLTE") {
            if (length % 3 != 0 || length == 0 || length > 768)
                throw Error("PNG PLTE chunk has the wrong length");
            palette = body;
        } else if (type == "tRNS") {
            transparency = body;
        } else if (type == "IDAT") {
            compressed += body;
        } else if (type == "IEND") {
            have_end = true;
        } else if (type == "tEXt" || type == "zTXt" || type == "iTXt") {
            read_text_chunk(type, body, result.metadata, text_budget);
        } else if (!(static_cast<unsigned char>(type[0]) & 0x20)) {
            // A lower-case first letter marks a chunk a reader may ignore; this one is not.
            throw Error("PNG file has an unknown critical chunk " + shown(type));
        }
    }
    if (h.colour == kPalette && palette.empty()) throw Error("PNG palette image has no PLTE");

    const std::vector<Pass> all = passes(h);
    std::size_t expected = 0;
    for (const Pass& p : all)
        if (p.width(h) > 0 && p.height(h) > 0)
            expected += (h.row_bytes(p.width(h)) + 1) * static_cast<std::size_t>(p.height(h));
    std::string raw = zlib_decompress(compressed, expected);
    if (raw.size() != expected) throw Error("PNG image data ends early");

    SampleImage& image = result.image;
    image.width = h.width;
    image.height = h.height;
    const bool alpha_palette = h.colour == kPalette && !transparency.empty();
    image.channels = h.colour == kPalette ? (alpha_palette ? 4 : 3) : h.channels();
    image.bits = h.depth == 16 ? 16 : 8;
    image.bytes.resize(image.row_bytes() * static_cast<std::size_t>(h.height));
    const std::size_t palette_size = palette.size() / 3;
    const unsigned low_max = (1u << h.depth) - 1;

    auto* data = reinterpret_cast<std::uint8_t*>(raw.data());
    const std::size_t bpp = static_cast<std::size_t>(std::max(1, h.bits_per_pixel() / 8));
    for (const Pass& p : all) {
        const int pw = p.width(h);
        const int ph = p.height(h);
        if (pw == 0 || ph == 0) continue;
        const std::size_t row = h.row_bytes(pw);
        unfilter(data, row, ph, bpp);
        for (int py = 0; py < ph; ++py) {
            const std::uint8_t* src = data + static_cast<std::size_t>(py) * (row + 1) + 1;
            const int y = p.y0 + py * p.dy;
            for (int px = 0; px < pw; ++px) {
                const int x = p.x0 + px * p.dx;
                std::uint8_t* dst = image.bytes.data() +
                                    static_cast<std::size_t>(y) * image.row_bytes() +
                                    static_cast<std::size_t>(x) * image.bytes_per_pixel();
                if (h.depth >= 8) {
                    const std::size_t n = static_cast<std::size_t>(h.bits_per_pixel() / 8);
                    const std::uint8_t* s = src + static_cast<std::size_t>(px) * n;
                    if (h.colour != kPalette) {
                        std::copy(s, s + n, dst);
                        continue;
                    }
                }
                // One sample of 1, 2, 4 or 8 bits: grey or a palette index.
                const std::size_t bit =
                    static_cast<std::size_t>(px) * static_cast<std::size_t>(h.depth);
                const unsigned shift = 8 - static_cast<unsigned>(h.depth) - bit % 8;
                const unsigned v = (src[bit / 8] >> shift) & low_max;
                if (h.colour != kPalette) {
                    dst[0] = static_cast<std::uint8_t>(v * 255 / low_max);
                    continue;
                }
                if (v >= palette_size) throw Error("PNG pixel refers past the end of its palette");
                for (std::size_t c = 0; c < 3; ++c)
                    dst[c] = static_cast<std::uint8_t>(palette[v * 3 + c]);
                if (alpha_palette)
                    dst[3] =
                        v < transparency.size() ? static_cast<std::uint8_t>(transparency[v]) : 255;
            }
        }
        data += (row + 1) * static_cast<std::size_t>(ph);
    }
    return result;
}

}  // namespace rt
