// PNG output: IHDR, the metadata as text chunks, the filtered rows compressed by rt's own
// deflate in IDAT chunks, IEND.
#include <array>
#include <cstdlib>
#include <optional>
#include <vector>

#include "common/message_text.h"
#include "image/deflate.h"
#include "png_format.h"
#include "rt/error.h"
#include "rt/image_io.h"

namespace rt {

namespace {

using namespace png_format;

// IDAT chunks of 64 KiB, as common encoders write; any size up to 2^31 - 1 is valid.
constexpr std::size_t kIdatSize = 65536;

void put_u32(std::string& out, std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>(v >> shift));
}

void put_chunk(std::string& out, std::string_view type, std::string_view body) {
    put_u32(out, static_cast<std::uint32_t>(body.size()));
    out += type;
    out += body;
    put_u32(out, crc32(body, crc32(type)));
}

// UTF-8 text (the metadata's) as Latin-1 (a PNG keyword's), or nothing when it holds a
// character beyond U+00FF or is not UTF-8.
std::optional<std::string> utf8_to_latin1(std::string_view text) {
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c < 0x80) {
            out.push_back(static_cast<char>(c));
            continue;
        }
        // Only the two-byte sequences C2 80 to C3 BF encode U+0080 to U+00FF.
        if ((c != 0xC2 && c != 0xC3) || i + 1 >= text.size()) return std::nullopt;
        const auto next = static_cast<unsigned char>(text[i + 1]);
        if ((next & 0xC0) != 0x80) return std::nullopt;
        out.push_back(static_cast<char>((c & 0x03) << 6 | (next & 0x3F)));
        ++i;
    }
    return out;
}

// A text record as a tEXt chunk, or an iTXt one when its value is not plain ASCII. The key is
// written in Latin-1, as the reader reads it, so that every keyword a PNG can hold survives a
// round trip; a key no PNG keyword can be, or a value holding a NUL (which would end it), is
// refused rather than changed.
void put_text(std::string& out, const std::string& key, const std::string& value) {
    const std::optional<std::string> keyword = utf8_to_latin1(key);
    if (!keyword || !valid_keyword(*keyword))
        throw Error(quote_token(key, kShowWhole) +
                    " cannot be a PNG text keyword (1 to 79 printable Latin-1 characters, no "
                    "leading, trailing or double spaces)");
    if (value.find('\0') != std::string::npos)
        throw Error("the value of " + quote_token(key, kShowWhole) +
                    " holds a NUL character, which PNG text cannot");
    std::string body = *keyword;
    body.push_back('\0');
    bool ascii = true;
    for (const char c : value) ascii = ascii && static_cast<unsigned char>(c) < 128;
    if (ascii) {
        body += value;
        put_chunk(out, "tEXt", body);
        return;
    }
    // tEXt is Latin-1; anything else (a file name in UTF-8) goes in an uncompressed iTXt,
    // with no language tag and no translated keyword.
    body.append(std::string_view("\0\0\0\0", 4));
    body += value;
    put_chunk(out, "iTXt", body);
}

// Each row with the filter whose output has the smallest sum of absolute values (the bytes
// read as signed): what libpng does, and a good guess at what deflate packs best.
std::string filter_rows(const SampleImage& image, const std::uint8_t* samples) {
    const std::size_t bpp = image.bytes_per_pixel();
    const std::size_t row = image.row_bytes();
    std::string out;
    out.reserve((row + 1) * static_cast<std::size_t>(image.height));
    const std::vector<std::uint8_t> zeros(row, 0);
    std::array<std::vector<std::uint8_t>, kFilterTypes> trial;
    for (auto& t : trial) t.resize(row);
    for (int y = 0; y < image.height; ++y) {
        const std::uint8_t* cur = samples + static_cast<std::size_t>(y) * row;
        const std::uint8_t* up = y == 0 ? zeros.data() : cur - row;
        std::array<std::uint64_t, kFilterTypes> cost{};
        for (std::size_t i = 0; i < row; ++i) {
            const std::uint8_t a = i >= bpp ? cur[i - bpp] : 0;
            const std::uint8_t c = i >= bpp ? up[i - bpp] : 0;
            for (int f = 0; f < kFilterTypes; ++f) {
                const auto v = static_cast<std::uint8_t>(cur[i] - predict(f, a, up[i], c));
                trial[f][i] = v;
                cost[f] += static_cast<std::uint64_t>(std::abs(static_cast<std::int8_t>(v)));
            }
        }
        int best = 0;
        for (int f = 1; f < kFilterTypes; ++f)
            if (cost[f] < cost[best]) best = f;
        out.push_back(static_cast<char>(best));
        out.append(reinterpret_cast<const char*>(trial[best].data()), row);
    }
    return out;
}

}  // namespace

std::string encode_png(const SampleImage& image, const ImageMetadata& metadata) {
    return encode_png(image, image.bytes.data(), metadata);
}

std::string encode_png(const SampleImage& image, const std::uint8_t* samples,
                       const ImageMetadata& metadata) {
    static constexpr std::array<int, 5> kColourType = {-1, kGrey, kGreyAlpha, kRgb, kRgbAlpha};
    if (image.channels < 1 || image.channels > 4 || (image.bits != 8 && image.bits != 16))
        throw Error("PNG cannot store this image");
    std::string out(kSignature);
    std::string header;
    put_u32(header, static_cast<std::uint32_t>(image.width));
    put_u32(header, static_cast<std::uint32_t>(image.height));
    header.push_back(static_cast<char>(image.bits));
    header.push_back(static_cast<char>(kColourType[image.channels]));
    header.append(3, '\0');  // deflate, adaptive filtering, no interlacing
    put_chunk(out, "IHDR", header);
    for (const auto& [key, value] : metadata.entries) put_text(out, key, value);
    const std::string data = zlib_compress(filter_rows(image, samples));
    for (std::size_t at = 0; at < data.size(); at += kIdatSize)
        put_chunk(out, "IDAT", std::string_view(data).substr(at, kIdatSize));
    put_chunk(out, "IEND", "");
    return out;
}

}  // namespace rt
