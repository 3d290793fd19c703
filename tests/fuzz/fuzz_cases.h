// The fuzz cases of every input surface besides rt's scene reader (fuzz_one.h): rtpp's
// compiler, NFF, PLY and OBJ, image decoding with a re-encode, inflate with a round trip, and
// three structured cases that build a valid file around fuzzed content and know what reading
// it must give (a PNG, the pieces of a merge, a checkpoint).
// Each is shared by its libFuzzer target (fuzz_*.cpp) and by ctest (test_fuzz_surfaces.cpp),
// which runs the seeds and every regression input through it. A case returns the problem it
// found, or "" for none: an input may be refused, but only with the error type its surface
// promises and a message that names its place; a re-encode must read back as it was.
#pragma once

#include <algorithm>
#include <bit>
#include <climits>
#include <cstdint>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "batch/checkpoint.h"
#include "fuzz_bytes.h"
#include "image/deflate.h"
#include "rt/error.h"
#include "rt/image_file.h"
#include "rt/image_io.h"
#include "rt/image_merge.h"
#include "rt/limits.h"
#include "rtpp/compiler.h"
#include "rtpp/nff.h"
#include "scene/mesh_file.h"

namespace rt_fuzz {

// rtpp: compile the bytes, with small limits so that each case takes milliseconds. Includes
// are looked for in a directory that does not exist. Any error must be a CompileError naming
// the source ("fuzz.rts:" first).
inline std::string rtpp_case(std::string_view bytes) {
    rtpp::CompileOptions options;
    options.limits.loop_iterations = 20'000;
    options.limits.objects = 20'000;
    options.limits.list_items = 20'000;
    // A few milliseconds of work: loops within the iteration limit can have long bodies.
    options.limits.steps = 200'000;
    options.limits.output_size = 16u << 20;
    try {
        rtpp::compile(std::string(bytes), "fuzz.rts", "/nonexistent/rt-fuzz", options);
    } catch (const rtpp::CompileError& e) {
        const std::string_view message = e.what();
        if (message.substr(0, 9) != "fuzz.rts:")
            return std::string("error without its place: ") + e.what();
    }
    return "";
}

// NFF through rtpp: errors are CompileErrors naming the input.
inline std::string nff_case(std::string_view bytes) {
    std::istringstream in{std::string(bytes)};
    std::ostringstream out;
    rtpp::NffOptions options;
    options.max_line_length = 1u << 16;
    options.max_polygon_vertices = 1u << 12;
    options.max_mesh_vertices = 1u << 12;
    options.max_lights = 1u << 8;
    try {
        rtpp::translate_nff(in, "fuzz.nff", out, options);
    } catch (const rtpp::CompileError& e) {
        const std::string_view message = e.what();
        if (message.substr(0, 9) != "fuzz.nff:")
            return std::string("error without its place: ") + e.what();
    }
    return "";
}

// PLY or OBJ (told from the bytes): errors are rt::Errors.
inline std::string mesh_case(std::string_view bytes) {
    try {
        rt::read_mesh_file(bytes, "fuzz.mesh");
    } catch (const rt::Error&) {
    }
    return "";
}

// An image: decoded, then written again as PNG (any channels), as PPM (grey or RGB) and as
// PFM, each read back: the samples and metadata must be what was decoded. An encoder may
// refuse metadata its format cannot hold (an rt::Error), never change it.
inline std::string image_case(std::string_view bytes) {
    rt::ImageFile image;
    try {
        image = rt::decode_image(bytes);
    } catch (const rt::Error&) {
        return "";
    }
    if (image.format == rt::ImageFormat::pfm) {
        const std::string again = rt::encode_pfm(rt::to_raster(image));
        const rt::ImageFile back = rt::decode_pfm(again);
        for (std::size_t i = 0; i < image.floats.size(); ++i) {
            const float a = image.floats[i], b = back.floats[i];
            if (!(a == b || (a != a && b != b))) return "PFM round trip changed a value";
        }
        return "";
    }
    try {
        const rt::DecodedImage png = rt::decode_png(rt::encode_png(image.samples, image.metadata));
        if (png.image.bytes != image.samples.bytes) return "PNG round trip changed the samples";
        if (png.metadata.entries != image.metadata.entries)
            return "PNG round trip changed the metadata";
    } catch (const rt::Error&) {
    }
    if (image.channels() == 1 || image.channels() == 3) {
        try {
            const rt::ImageFile ppm = rt::decode_ppm(rt::encode_ppm(image.samples, image.metadata));
            if (ppm.samples.bytes != image.samples.bytes)
                return "PPM round trip changed the samples";
            if (ppm.metadata.entries != image.metadata.entries)
                return "PPM round trip changed the metadata";
        } catch (const rt::Error&) {
        }
    }
    return "";
}

// Inflate: a stream that decodes must survive our deflate and back; and any bytes must
// survive deflate and inflate.
inline std::string inflate_case(std::string_view bytes) {
    try {
        // 128 KiB, four windows: every distance and length a stream can give, and the limit
        // reached; at megabytes every input's round trip would take the time of thousands.
        const std::string data = rt::inflate(bytes, std::size_t{1} << 17);
        if (rt::zlib_decompress(rt::zlib_compress(data), data.size()) != data)
            return "inflated data did not survive a round trip";
    } catch (const rt::Error&) {
    }
    if (rt::inflate(rt::deflate(bytes), bytes.size()) != bytes)
        return "the input did not survive deflate and inflate";
    return "";
}

// The structured cases' own model of the formats, written from the specifications rather
// than taken from the code under test, so that what they expect is not what it does.
namespace model {

inline void put_be32(std::string& out, std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>((v >> shift) & 0xff);
}

// A PNG chunk: length, type, body and the CRC of type and body (wrong when asked).
inline std::string png_chunk(std::string_view type, std::string_view body, bool good_crc) {
    std::string out;
    put_be32(out, static_cast<std::uint32_t>(body.size()));
    out += type;
    out += body;
    const std::uint32_t crc = rt::crc32(body, rt::crc32(type));
    put_be32(out, good_crc ? crc : crc ^ 0x80000000u);
    return out;
}

// ISO/IEC 15948 11.3.4.2: 1-79 Latin-1 characters of 32-126 or 161-255, no leading,
// trailing or consecutive spaces.
inline bool png_keyword_allowed(std::string_view keyword) {
    if (keyword.empty() || keyword.size() > 79) return false;
    if (keyword.front() == ' ' || keyword.back() == ' ') return false;
    if (keyword.find("  ") != std::string_view::npos) return false;
    return std::all_of(keyword.begin(), keyword.end(), [](char ch) {
        const auto c = static_cast<unsigned char>(ch);
        return (c >= 32 && c <= 126) || c >= 161;
    });
}

inline std::string latin1_as_utf8(std::string_view text) {
    std::string out;
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if (c < 0x80) {
            out += ch;
        } else {
            out += static_cast<char>(0xC0 | (c >> 6));
            out += static_cast<char>(0x80 | (c & 0x3F));
        }
    }
    return out;
}

// The filter prediction of ISO/IEC 15948 9.2 from left (a), up (b) and upper-left (c).
inline int png_prediction(int type, int a, int b, int c) {
    switch (type) {
        case 1:
            return a;
        case 2:
            return b;
        case 3:
            return (a + b) / 2;
        case 4: {
            const int p = a + b - c;
            const int pa = p > a ? p - a : a - p;
            const int pb = p > b ? p - b : b - p;
            const int pc = p > c ? p - c : c - p;
            return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
        }
        default:
            return 0;
    }
}

// Whole numbers between separators, exactly `count` of them, each at most INT_MAX, digits
// only: how a Region ("x0,x1,y0,y1") or Full-Size ("WxH") record reads.
inline bool record_numbers(std::string_view text, char separator, int count, long long* out) {
    for (int i = 0; i < count; ++i) {
        if (i > 0) {
            if (text.empty() || text.front() != separator) return false;
            text.remove_prefix(1);
        }
        std::size_t digits = 0;
        long long v = 0;
        while (digits < text.size() && text[digits] >= '0' && text[digits] <= '9') {
            v = v * 10 + (text[digits] - '0');
            if (v > INT_MAX) return false;
            ++digits;
        }
        if (digits == 0) return false;
        out[i] = v;
        text.remove_prefix(digits);
    }
    return text.empty();
}

// A zlib stream of stored blocks (RFC 1950, 1951 3.2.4) of fuzzed sizes, as a cheap and
// independent writer: rt's deflate allocates half a megabyte of match tables for each stream,
// which would be most of a case's time.
inline std::string zlib_stored(std::string_view data, FuzzBytes& in) {
    std::string out("\x78\x01", 2);
    std::string_view left = data;
    do {
        const std::size_t size = std::min<std::size_t>(left.size(), 65535 - in.below(65535));
        out += static_cast<char>(size == left.size() ? 1 : 0);  // stored; the last?
        const auto length = static_cast<std::uint16_t>(size);
        const auto complement = static_cast<std::uint16_t>(~length);
        for (const std::uint16_t v : {length, complement}) {
            out += static_cast<char>(v & 0xff);
            out += static_cast<char>(v >> 8);
        }
        out += left.substr(0, size);
        left.remove_prefix(size);
    } while (!left.empty());
    put_be32(out, rt::adler32(data));
    return out;
}

}  // namespace model

// A structured PNG: IHDR, PLTE and tRNS, the image data (rows filtered with fuzzed filter
// types, deflated by rt's zlib, split over fuzzed IDAT chunks), text chunks of all three kinds
// and ancillary chunks at fuzzed places, all with valid CRCs; rarely, one thing is wrong
// (a field, a length, a CRC, the order). Where the case knows the answer, decode_png must give
// it: the samples the case put in, its text as UTF-8, or a refusal when the file breaks a rule
// the decoder promises to check. A decoded file is then given to image_case's re-encodes.
inline std::string png_case(std::string_view bytes) {
    using model::png_chunk;
    FuzzBytes in(bytes);
    bool exact = true;      // whether the case knows what decoding must give
    std::string must_fail;  // the broken rule, when decoding must be refused
    const auto fail = [&](const char* why) {
        if (must_fail.empty()) must_fail = why;
    };

    // IHDR.
    static constexpr int kColours[5] = {0, 2, 3, 4, 6};
    static constexpr int kDepths[5][5] = {
        {1, 2, 4, 8, 16}, {8, 16, 0, 0, 0}, {1, 2, 4, 8, 0}, {8, 16, 0, 0, 0}, {8, 16, 0, 0, 0}};
    static constexpr std::uint32_t kDepthCounts[5] = {5, 2, 4, 2, 2};
    const std::uint32_t kind = in.below(5);
    int colour = kColours[kind];
    int depth = kDepths[kind][in.below(kDepthCounts[kind])];
    if (in.rare(32)) {
        colour = in.byte();
        depth = in.byte();
    }
    int channels = 0;  // in the file: a palette index is one
    for (std::uint32_t k = 0; k < 5; ++k)
        if (colour == kColours[k])
            for (std::uint32_t d = 0; d < kDepthCounts[k]; ++d)
                if (depth == kDepths[k][d])
                    channels = colour == 2 ? 3 : colour == 4 ? 2 : colour == 6 ? 4 : 1;
    if (channels == 0) fail("an invalid colour type and bit depth");
    std::uint32_t width = 1 + in.below(16), height = 1 + in.below(16);
    if (in.rare(32)) {
        width = in.u32();
        height = in.u32();
    }
    if (width == 0 || height == 0) fail("no pixels");
    if (width > 0x7FFFFFFFu || height > 0x7FFFFFFFu ||
        std::uint64_t{width} * height > static_cast<std::uint64_t>(rt::kMaxImagePixels))
        fail("more pixels than the image library reads");
    int interlace = static_cast<int>(in.below(2));
    if (in.rare(64)) interlace = in.byte();
    if (interlace > 1) fail("an unknown interlace method");
    std::string header;
    model::put_be32(header, width);
    model::put_be32(header, height);
    header += static_cast<char>(depth);
    header += static_cast<char>(colour);
    for (int field = 0; field < 2; ++field) {  // compression and filter method: 0 only
        const char method = in.rare(64) ? static_cast<char>(in.byte()) : '\0';
        if (method != 0) fail("an unknown compression or filter method");
        header += method;
    }
    header += static_cast<char>(interlace);

    // PLTE and tRNS.
    std::string palette;
    if (colour == 3 || in.rare(8)) {
        palette = in.exactly(3 * (1 + in.below(256)));
        if (colour == 0 || colour == 4) exact = false;  // PLTE is forbidden there
        if (in.rare(32)) {                              // (an empty one is not written)
            palette.resize(in.below(800));
            if (!palette.empty() && (palette.size() % 3 != 0 || palette.size() > 768))
                fail("a PLTE of the wrong length");
        }
    }
    const bool drop_palette = colour == 3 && in.rare(32);
    if (colour == 3 && (drop_palette || palette.empty())) fail("a palette image without PLTE");
    std::string transparency;
    const bool has_transparency = in.below(3) == 0;
    if (has_transparency) {
        const std::size_t entries = palette.size() / 3;
        if (colour == 3)
            transparency = in.exactly(in.below(static_cast<std::uint32_t>(entries) + 1));
        else
            transparency = in.exactly(colour == 2 ? 6 : 2);
        if (colour == 4 || colour == 6 || in.rare(32)) {  // forbidden, or of a wrong length
            transparency = in.exactly(in.below(300));
            exact = false;
        }
    }

    // The image data, and the samples decoding must give.
    const bool modelled = must_fail.empty() && std::uint64_t{width} * height <= 4096;
    if (must_fail.empty() && !modelled) exact = false;
    rt::SampleImage expected;
    std::string raw;
    if (modelled) {
        const int w = static_cast<int>(width), h = static_cast<int>(height);
        expected.width = w;
        expected.height = h;
        expected.channels = colour == 3 ? (transparency.empty() ? 3 : 4) : channels;
        expected.bits = depth == 16 ? 16 : 8;
        expected.bytes.resize(expected.row_bytes() * static_cast<std::size_t>(h));
        const std::size_t entries = palette.size() / 3;
        const int pixel_bits = channels * depth;
        const std::size_t filter_distance = static_cast<std::size_t>(std::max(1, pixel_bits / 8));
        struct Pass {
            int x0, y0, dx, dy;
        };
        static constexpr Pass kAdam7[7] = {{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4},
                                           {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}};
        const Pass whole[1] = {{0, 0, 1, 1}};
        const Pass* passes = interlace == 1 ? kAdam7 : whole;
        for (int p = 0; p < (interlace == 1 ? 7 : 1); ++p) {
            const Pass& pass = passes[p];
            const int pw = w > pass.x0 ? (w - pass.x0 + pass.dx - 1) / pass.dx : 0;
            const int ph = h > pass.y0 ? (h - pass.y0 + pass.dy - 1) / pass.dy : 0;
            if (pw == 0 || ph == 0) continue;
            const std::size_t row_bytes = (static_cast<std::size_t>(pw) * pixel_bits + 7) / 8;
            std::string previous(row_bytes, '\0');
            for (int py = 0; py < ph; ++py) {
                const std::string row = in.exactly(row_bytes);
                int filter = static_cast<int>(in.below(5));
                if (in.rare(64)) filter = in.byte();
                if (filter > 4) fail("an unknown filter type");
                raw += static_cast<char>(filter);
                for (std::size_t i = 0; i < row_bytes; ++i) {
                    const auto at = [](const std::string& s, std::size_t k, std::size_t back) {
                        return k >= back ? static_cast<unsigned char>(s[k - back]) : 0;
                    };
                    const int a = at(row, i, filter_distance), b = at(previous, i, 0);
                    const int c = at(previous, i, filter_distance);
                    raw += static_cast<char>(static_cast<unsigned char>(row[i]) -
                                             model::png_prediction(filter, a, b, c));
                }
                previous = row;
                const int y = pass.y0 + py * pass.dy;
                for (int px = 0; px < pw; ++px) {
                    const int x = pass.x0 + px * pass.dx;
                    std::uint8_t* out = expected.bytes.data() +
                                        static_cast<std::size_t>(y) * expected.row_bytes() +
                                        static_cast<std::size_t>(x) * expected.bytes_per_pixel();
                    if (depth >= 8 && colour != 3) {
                        const std::size_t n = static_cast<std::size_t>(pixel_bits / 8);
                        for (std::size_t k = 0; k < n; ++k)
                            out[k] = static_cast<std::uint8_t>(
                                row[static_cast<std::size_t>(px) * n + k]);
                        continue;
                    }
                    const std::size_t bit = static_cast<std::size_t>(px) * depth;
                    const unsigned top = (1u << depth) - 1;
                    const unsigned v = (static_cast<unsigned char>(row[bit / 8]) >>
                                        (8 - depth - static_cast<int>(bit % 8))) &
                                       top;
                    if (colour != 3) {
                        out[0] = static_cast<std::uint8_t>(v * 255 / top);
                    } else if (v >= entries) {
                        fail("a pixel past the end of its palette");
                    } else {
                        for (std::size_t k = 0; k < 3; ++k)
                            out[k] = static_cast<std::uint8_t>(palette[3 * v + k]);
                        if (!transparency.empty())
                            out[3] = v < transparency.size()
                                         ? static_cast<std::uint8_t>(transparency[v])
                                         : 255;
                    }
                }
            }
        }
        if (in.rare(32)) {  // data of the wrong length
            if (in.below(2) == 0)
                raw.pop_back();
            else
                raw += static_cast<char>(in.byte());
            fail("image data of the wrong length");
        }
    } else {
        raw = in.take(in.below(2048));
    }
    // Mostly stored blocks; rt's deflate for one stream in eight, for inflate's other paths.
    std::string stream = in.below(8) == 7 ? rt::zlib_compress(raw) : model::zlib_stored(raw, in);
    if (in.rare(32)) {
        const std::size_t at = in.below(static_cast<std::uint32_t>(stream.size()));
        stream[at] = static_cast<char>(stream[at] ^ (1 + in.below(255)));
        exact = false;
    }

    // Text chunks, and the metadata decoding must give.
    // (Chunks before the image data are read first: each list keeps its metadata in order.)
    rt::ImageMetadata text, text_after;
    std::vector<std::pair<std::string, std::string>> before_data, after_data;
    for (std::uint32_t n = in.below(4); n > 0; --n) {
        static constexpr std::string_view kKeywordChars{"Software Title\xe9\xff\x7f\x01~:"};
        std::string keyword = in.word(kKeywordChars, 12);
        if (in.rare(16)) keyword = std::string(in.take(in.below(90)));
        if (keyword.find('\0') != std::string::npos) exact = false;  // it ends the keyword early
        if (!model::png_keyword_allowed(keyword)) fail("an invalid keyword");
        static constexpr std::string_view kTextChars{"rt 0.1 \n\t\xe9\xa0=%:x"};
        std::string value = in.word(kTextChars, 24);
        if (in.rare(32)) {
            value.insert(in.below(static_cast<std::uint32_t>(value.size()) + 1), 1, '\0');
            fail("a NUL in its text");
        }
        const bool before = in.below(2) == 0;
        rt::ImageMetadata& read_as = before ? text : text_after;
        std::string body = keyword + '\0';
        std::string type;
        switch (in.below(3)) {
            case 0:
                type = "tEXt";
                body += value;
                read_as.set(model::latin1_as_utf8(keyword), model::latin1_as_utf8(value));
                break;
            case 1: {
                type = "zTXt";
                const char method = in.rare(32) ? static_cast<char>(in.byte()) : '\0';
                if (method != 0) fail("an unknown text compression");
                body += method;
                std::string packed =
                    in.below(8) == 7 ? rt::zlib_compress(value) : model::zlib_stored(value, in);
                if (in.rare(32)) {
                    packed.resize(in.below(static_cast<std::uint32_t>(packed.size())));
                    fail("a truncated zTXt stream");
                }
                body += packed;
                read_as.set(model::latin1_as_utf8(keyword), model::latin1_as_utf8(value));
                break;
            }
            default: {
                type = "iTXt";
                // The text is UTF-8 here: Latin-1 made UTF-8 keeps it valid.
                const std::string utf8 = model::latin1_as_utf8(value);
                const bool compressed = in.below(2) == 1;
                body += compressed ? '\1' : '\0';
                body += in.rare(32) ? static_cast<char>(in.byte()) : '\0';
                body += in.word("enfr-", 5) + '\0';
                body += model::latin1_as_utf8(in.word("Titel \xe9", 6)) + '\0';
                body += !compressed        ? utf8
                        : in.below(8) == 7 ? rt::zlib_compress(utf8)
                                           : model::zlib_stored(utf8, in);
                if (body[keyword.size() + 2] != 0) exact = false;  // an unknown method
                read_as.set(model::latin1_as_utf8(keyword), utf8);
            }
        }
        (before ? before_data : after_data).emplace_back(type, body);
    }
    for (auto& [key, value] : text_after.entries) text.set(key, std::move(value));

    // The chunks in order, then rarely one change to the order or a CRC.
    std::vector<std::pair<std::string, std::string>> chunks;
    chunks.emplace_back("IHDR", header);
    if (!palette.empty() && !drop_palette) chunks.emplace_back("PLTE", palette);
    if (has_transparency) chunks.emplace_back("tRNS", transparency);
    chunks.insert(chunks.end(), before_data.begin(), before_data.end());
    if (in.rare(4)) {  // an ancillary chunk the decoder skips
        static constexpr const char* kAncillary[4] = {"tIME", "gAMA", "bKGD", "ruSt"};
        chunks.emplace_back(kAncillary[in.below(4)], std::string(in.take(in.below(32))));
    }
    for (std::uint32_t left = 1 + in.below(4); left > 0; --left) {
        const std::size_t part =
            left == 1 ? stream.size() : in.below(static_cast<std::uint32_t>(stream.size()) + 1);
        chunks.emplace_back("IDAT", stream.substr(0, part));
        stream.erase(0, part);
    }
    chunks.insert(chunks.end(), after_data.begin(), after_data.end());
    if (in.rare(32)) {
        chunks.emplace_back(in.below(2) == 0 ? "CrIT" : std::string(in.exactly(4)), "");
        if (chunks.back().first == "CrIT")
            fail("an unknown critical chunk");
        else
            exact = false;
    }
    chunks.emplace_back("IEND", "");
    const auto pick = [&] { return in.below(static_cast<std::uint32_t>(chunks.size())); };
    if (in.rare(32)) {
        // One choice at a time: the order in which arguments are evaluated is the compiler's.
        const std::uint32_t change = in.below(3), one = pick(), other = pick();
        if (change == 0) {
            std::swap(chunks[one], chunks[other]);
        } else if (change == 1) {
            const auto copy = chunks[other];
            chunks.insert(chunks.begin() + one, copy);
        } else {
            chunks.erase(chunks.begin() + one);
        }
        exact = false;
    }
    const std::size_t bad_crc = in.rare(32) ? pick() : chunks.size();
    if (bad_crc < chunks.size()) fail("a wrong CRC");
    std::string file("\x89PNG\r\n\x1a\n", 8);
    for (std::size_t i = 0; i < chunks.size(); ++i)
        file += png_chunk(chunks[i].first, chunks[i].second, i != bad_crc);
    if (in.rare(32)) {
        file.resize(in.below(static_cast<std::uint32_t>(file.size())));
        fail("the file cut short");
    }
    file += in.take(in.below(64));  // what follows IEND is not read

    rt::DecodedImage decoded;
    try {
        decoded = rt::decode_png(file);
    } catch (const rt::Error& e) {
        if (exact && must_fail.empty()) return std::string("refused a valid PNG: ") + e.what();
        return "";
    }
    // The re-encodes of image_case, for one decoded file in eight (each is three more deflates).
    const bool reencode = in.below(8) == 7;
    if (!exact) return reencode ? image_case(file) : "";
    if (!must_fail.empty()) return "accepted a PNG with " + must_fail;
    const rt::SampleImage& got = decoded.image;
    if (got.width != expected.width || got.height != expected.height ||
        got.channels != expected.channels || got.bits != expected.bits)
        return "decoded a PNG to the wrong size, channels or bit depth";
    if (got.bytes != expected.bytes) return "decoded a PNG to the wrong samples";
    if (decoded.metadata.entries != text.entries) return "decoded a PNG's text wrongly";
    return reencode ? image_case(file) : "";
}

// A merge: a fuzzed full image (PNG or PPM, any channels the format holds, 8 or 16 bits) cut
// into a grid of pieces, each written with the metadata rt --region writes (the Region and
// Full-Size records at fuzzed places among the rest), decoded, and given to merge_pieces in a
// fuzzed order; rarely, a record is fuzzed text, a piece is missing, doubled, cropped, of
// another depth or format, or made differently. Unchanged pieces must merge to the full image;
// a change the case knows breaks them must be refused; and whatever merges must be what the
// pieces' own records say, checked here from those records: each region inside one full size,
// every pixel in exactly one piece and copied from it.
inline std::string merge_case(std::string_view bytes) {
    FuzzBytes in(bytes);
    bool exact = true;
    std::string must_fail;
    const auto fail = [&](const char* why) {
        if (must_fail.empty()) must_fail = why;
    };

    const bool png = in.below(2) == 0;
    rt::SampleImage full;
    full.width = 1 + static_cast<int>(in.below(24));
    full.height = 1 + static_cast<int>(in.below(24));
    full.channels = png ? 1 + static_cast<int>(in.below(4)) : in.below(2) == 0 ? 1 : 3;
    full.bits = in.below(2) == 0 ? 8 : 16;
    const std::string samples =
        in.exactly(full.row_bytes() * static_cast<std::size_t>(full.height));
    full.bytes.assign(samples.begin(), samples.end());
    rt::ImageMetadata made;
    made.set("Software", "rt 0.1.0");
    for (std::uint32_t n = in.below(3); n > 0; --n)
        made.set(in.word("ABCDSceneOptions-", 8), in.word("abc012 .,=-_:", 16));

    // The grid's cuts.
    const auto cuts = [&](int size) {
        std::vector<int> at{0, size};
        for (std::uint32_t n = size > 1 ? in.below(4) : 0; n > 0; --n)
            at.push_back(1 + static_cast<int>(in.below(static_cast<std::uint32_t>(size - 1))));
        std::sort(at.begin(), at.end());
        at.erase(std::unique(at.begin(), at.end()), at.end());
        return at;
    };
    const std::vector<int> xs = cuts(full.width), ys = cuts(full.height);
    struct Piece {
        rt::PixelRect rect;
        rt::ImageMetadata metadata;
        int bits;
        bool png;
    };
    std::vector<Piece> pieces;
    for (std::size_t j = 0; j + 1 < ys.size(); ++j)
        for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
            Piece piece{{xs[i], ys[j], xs[i + 1], ys[j + 1]}, made, full.bits, png};
            auto& entries = piece.metadata.entries;
            const std::string region = std::to_string(xs[i]) + "," + std::to_string(xs[i + 1]) +
                                       "," + std::to_string(ys[j]) + "," +
                                       std::to_string(ys[j + 1]);
            const std::string size = std::to_string(full.width) + "x" + std::to_string(full.height);
            std::uint32_t place = in.below(static_cast<std::uint32_t>(entries.size()) + 1);
            entries.insert(entries.begin() + place, {std::string(rt::kRegionKey), region});
            place = in.below(static_cast<std::uint32_t>(entries.size()) + 1);
            entries.insert(entries.begin() + place, {std::string(rt::kFullSizeKey), size});
            pieces.push_back(std::move(piece));
        }
    for (std::size_t i = pieces.size(); i > 1; --i)
        std::swap(pieces[i - 1], pieces[in.below(static_cast<std::uint32_t>(i))]);

    // Rarely, one change.
    std::vector<std::uint32_t> cropped(pieces.size(), 0);
    if (in.rare(8)) {
        const std::uint32_t change = in.below(8);
        const std::uint32_t which = in.below(static_cast<std::uint32_t>(pieces.size()));
        Piece& p = pieces[which];
        const std::string key(in.below(2) == 0 ? rt::kRegionKey : rt::kFullSizeKey);
        switch (change) {
            case 0:  // a record of fuzzed text
                p.metadata.set(key, in.word("0123456789,x-+ ", 24));
                exact = false;
                break;
            case 1: {  // a record of fuzzed numbers, any size
                std::string numbers = std::to_string(in.u32());
                for (int k = key == rt::kRegionKey ? 3 : 1; k > 0; --k)
                    numbers += (key == rt::kRegionKey ? "," : "x") + std::to_string(in.below(64));
                p.metadata.set(key, numbers);
                exact = false;
                break;
            }
            case 2:  // a record missing
                std::erase_if(p.metadata.entries, [&](const auto& e) { return e.first == key; });
                fail("a piece without its Region or Full-Size");
                break;
            case 3:
                pieces.erase(pieces.begin() + which);
                fail("a piece missing");
                break;
            case 4: {
                const Piece copy = p;
                pieces.push_back(copy);
                fail("a piece given twice");
                break;
            }
            case 5:  // (a lone piece has nothing to differ from)
                p.metadata.set(in.below(2) == 0 ? "Software" : "Other", "other");
                if (pieces.size() > 1) fail("a piece made differently");
                break;
            case 6:
                if (p.png && full.channels != 1 && full.channels != 3) {
                    p.bits = 24 - p.bits;
                    fail("a piece of another bit depth");
                } else {
                    p.png = !p.png;
                    fail("a piece of another format");
                }
                if (pieces.size() == 1) {
                    must_fail.clear();
                    exact = false;
                }
                break;
            default:
                cropped[which] = 1;
                fail("a piece smaller than its region");
        }
    }

    // Each piece written and decoded as rtimg merge reads its files, for one input in 32;
    // else made as decoding makes it (rt's PNG encoder deflates with half a megabyte of tables
    // for each piece, which would be most of the case's time).
    const bool write_files = in.below(32) == 31;
    std::vector<rt::ImagePiece> decoded;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
        const Piece& p = pieces[i];
        rt::SampleImage part;
        part.width = p.rect.width();
        part.height = p.rect.height() - static_cast<int>(i < cropped.size() ? cropped[i] : 0);
        part.channels = full.channels;
        part.bits = p.bits;
        for (int y = p.rect.y0; y < p.rect.y0 + part.height; ++y)
            for (int x = p.rect.x0; x < p.rect.x1; ++x)
                for (int c = 0; c < full.channels; ++c) {
                    const unsigned v = full.sample(x, y, c);
                    if (part.bits == 16) {
                        const unsigned wide = full.bits == 16 ? v : v * 257;
                        part.bytes.push_back(static_cast<std::uint8_t>(wide >> 8));
                        part.bytes.push_back(static_cast<std::uint8_t>(wide & 0xff));
                    } else {
                        part.bytes.push_back(
                            static_cast<std::uint8_t>(full.bits == 16 ? v >> 8 : v));
                    }
                }
        const std::string name = "piece" + std::to_string(i) + (p.png ? ".png" : ".ppm");
        if (!write_files) {
            rt::ImageFile image;
            image.format = p.png ? rt::ImageFormat::png : rt::ImageFormat::ppm;
            image.variant = p.png ? "PNG" : part.channels == 3 ? "P6" : "P5";
            image.samples = std::move(part);
            image.metadata = p.metadata;
            decoded.push_back({name, std::move(image)});
            continue;
        }
        try {
            const std::string file =
                p.png ? rt::encode_png(part, p.metadata) : rt::encode_ppm(part, p.metadata);
            decoded.push_back({name, rt::decode_image(file)});
        } catch (const rt::Error& e) {
            if (exact && must_fail.empty())
                return "could not write and read back " + name + ": " + e.what();
            return "";
        }
    }

    rt::ImageFile merged;
    try {
        merged = rt::merge_pieces(decoded);
    } catch (const rt::Error& e) {
        if (exact && must_fail.empty()) return std::string("refused pieces that tile: ") + e.what();
        return "";
    }
    if (exact && !must_fail.empty()) return "merged pieces with " + must_fail;

    // What merged must be what the pieces record.
    long long size[2] = {0, 0};
    std::vector<unsigned char> covered;
    for (const rt::ImagePiece& p : decoded) {
        const std::string* region = p.image.metadata.find(rt::kRegionKey);
        const std::string* full_size = p.image.metadata.find(rt::kFullSizeKey);
        long long r[4], s[2];
        if (region == nullptr || full_size == nullptr ||
            !model::record_numbers(*region, ',', 4, r) ||
            !model::record_numbers(*full_size, 'x', 2, s))
            return "merged " + p.name + ", which records no valid region";
        if (&p == &decoded.front()) {
            size[0] = s[0];
            size[1] = s[1];
            if (size[0] * size[1] > rt::kMaxImagePixels) return "merged beyond the pixel limit";
            if (merged.width() != size[0] || merged.height() != size[1])
                return "the merged image is not its recorded full size";
            covered.assign(static_cast<std::size_t>(size[0] * size[1]), 0);
        }
        if (s[0] != size[0] || s[1] != size[1]) return "merged pieces of two full sizes";
        if (!(r[0] < r[1] && r[1] <= size[0] && r[2] < r[3] && r[3] <= size[1]))
            return "merged " + p.name + ", whose region is outside its full image";
        if (p.image.width() != r[1] - r[0] || p.image.height() != r[3] - r[2])
            return "merged " + p.name + ", whose size is not its region's";
        if (p.image.format != decoded.front().image.format ||
            p.image.samples.bits != decoded.front().image.samples.bits ||
            p.image.channels() != decoded.front().image.channels())
            return "merged pieces of different formats";
        for (long long y = r[2]; y < r[3]; ++y)
            for (long long x = r[0]; x < r[1]; ++x) {
                if (covered[static_cast<std::size_t>(y * size[0] + x)]++ != 0)
                    return "merged pieces that overlap";
                for (int c = 0; c < p.image.channels(); ++c)
                    if (merged.samples.sample(static_cast<int>(x), static_cast<int>(y), c) !=
                        p.image.samples.sample(static_cast<int>(x - r[0]),
                                               static_cast<int>(y - r[2]), c))
                        return "the merged image differs from " + p.name;
            }
    }
    if (std::find(covered.begin(), covered.end(), 0) != covered.end())
        return "merged pieces that leave a gap";
    rt::ImageMetadata without = decoded.front().image.metadata;
    std::erase_if(without.entries, [](const auto& e) {
        return e.first == rt::kRegionKey || e.first == rt::kFullSizeKey;
    });
    if (merged.metadata.entries != without.entries) return "the merged image's metadata is wrong";
    if (exact && merged.samples.bytes != full.bytes) return "the merged image is not the full one";
    return "";
}

// A checkpoint: rows and a header built from the bytes (or, for some inputs, the bytes as they
// are), then rarely cut short, changed at one byte or followed by more bytes. Whatever
// read_checkpoint keeps must be exactly the file up to kept_bytes, written again; and of a
// file built here it keeps the header and every row whose record ends before the damage.
inline std::string checkpoint_case(std::string_view bytes) {
    FuzzBytes in(bytes);
    const std::uint32_t mode = in.below(8);
    std::string file;
    rt::CheckpointHeader header;
    std::vector<rt::CheckpointRow> rows;
    std::vector<std::size_t> ends;  // where each record ends, the header's first
    std::size_t intact = 0;         // the bytes before the damage
    bool appended = false;
    if (mode < 2) {
        if (mode == 1) file = rt::kCheckpointMagic;
        file += in.take(1 << 20);
    } else {
        for (std::uint32_t n = in.below(6); n > 0; --n)
            header.emplace_back(in.word("abcdefghijklmnopqrstuvwxyz-", 12),
                                in.word("0123456789abcdef .:x/,=", 24));
        file = rt::encode_checkpoint_start(header);
        ends.push_back(file.size());
        for (std::uint32_t n = in.below(6); n > 0; --n) {
            rt::CheckpointRow row;
            row.pass = static_cast<std::uint8_t>(in.below(2));
            row.y = in.rare(8) ? in.u32() : in.below(64);
            row.x0 = in.rare(8) ? in.u32() : in.below(64);
            for (std::uint32_t k = 3 * in.below(6); k > 0; --k) {
                const std::uint64_t value_bits = in.u64();
                row.values.push_back(std::bit_cast<double>(value_bits));
            }
            file += rt::encode_checkpoint_row(row);
            ends.push_back(file.size());
            rows.push_back(std::move(row));
        }
        intact = file.size();
        switch (in.below(4)) {
            case 0:
                break;
            case 1:
                intact = in.below(static_cast<std::uint32_t>(file.size()) + 1);
                file.resize(intact);
                break;
            case 2:
                intact = in.below(static_cast<std::uint32_t>(file.size()));
                file[intact] = static_cast<char>(file[intact] ^ (1 + in.below(255)));
                break;
            default:
                file += in.take(in.below(64));
                appended = true;
        }
    }

    rt::CheckpointContents contents;
    try {
        contents = rt::read_checkpoint(file);
    } catch (const rt::Error&) {
        if (mode >= 2 && intact >= ends.front())
            return "refused a checkpoint whose header is intact";
        return "";
    }
    if (contents.kept_bytes > file.size() ||
        contents.damaged != (contents.kept_bytes != file.size()))
        return "kept_bytes or damaged do not describe the file";
    std::string again = rt::encode_checkpoint_start(contents.header);
    for (const rt::CheckpointRow& row : contents.rows) again += rt::encode_checkpoint_row(row);
    if (std::string_view(file).substr(0, contents.kept_bytes) != again)
        return "what a checkpoint keeps is not the file up to kept_bytes";
    if (mode < 2) return "";
    if (intact < ends.front()) return "read a checkpoint whose header is damaged";
    if (contents.header != header) return "read a checkpoint's header wrongly";
    std::size_t kept = 0;
    while (kept < rows.size() && ends[kept + 1] <= intact) ++kept;
    // (Bytes appended may hold a record of their own; written again, it is checked above.)
    if (appended ? contents.rows.size() < kept || contents.kept_bytes < ends[kept]
                 : contents.rows.size() != kept || contents.kept_bytes != ends[kept])
        return "kept " + std::to_string(contents.rows.size()) + " rows of a checkpoint, not " +
               std::to_string(kept);
    return "";
}

}  // namespace rt_fuzz
