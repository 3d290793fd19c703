// The image library: checksums, deflate and inflate, PNG, PPM and PFM encoding, the value
// mapping, reading PNG files another encoder wrote.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "check.h"
#include "cli_util.h"
#include "image/deflate.h"
#include "rt/error.h"
#include "rt/image_io.h"
#include "scene/texture.h"

using namespace rt_test;
using namespace std::string_view_literals;
namespace fs = std::filesystem;

namespace {

std::uint32_t be32(std::string_view s, std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = v << 8 | static_cast<unsigned char>(s[at + i]);
    return v;
}

std::string random_bytes(std::size_t n, std::uint64_t seed, unsigned modulus = 256) {
    Random random(seed);
    std::string s(n, '\0');
    for (char& c : s) c = static_cast<char>(random.next() % modulus);
    return s;
}

// Round trips through both of rt's formats of compressed data.
void check_round_trip(const std::string& data) {
    const std::string packed = rt::deflate(data);
    CHECK(rt::inflate(packed, data.size()) == data);
    CHECK(rt::zlib_decompress(rt::zlib_compress(data), data.size()) == data);
}

bool throws_error(const std::function<void()>& f) {
    try {
        f();
    } catch (const rt::Error&) {
        return true;
    }
    return false;
}

// The pieces `encode(sink)` hands its sink, joined, and how many there were.
template <typename Encode>
std::pair<std::string, int> joined_pieces(const Encode& encode) {
    std::string joined;
    int pieces = 0;
    encode([&](std::string_view piece) {
        joined += piece;
        ++pieces;
    });
    return {joined, pieces};
}

rt::Raster raster_of(int width, int height, const std::vector<double>& values) {
    rt::Raster r(width, height);
    std::size_t i = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x, i += 3)
            r.set(x, y, {values[i], values[i + 1], values[i + 2]});
    return r;
}

// A smooth gradient with noise, so the filters and the matcher all have work.
rt::Raster busy_raster(int width, int height) {
    rt::Raster r(width, height);
    Random random(7);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            r.set(x, y,
                  {x / double(width), y / double(height),
                   0.5 + 0.5 * std::sin(x * 0.1) * std::cos(y * 0.07) + 0.02 * random.uniform()});
    return r;
}

}  // namespace

TEST(crc32_and_adler32_known_values) {
    CHECK_EQ(rt::crc32("123456789"), 0xCBF43926u);
    CHECK_EQ(rt::crc32(""), 0u);
    CHECK_EQ(rt::crc32("IEND"), 0xAE426082u);  // the fixed CRC every PNG ends with
    CHECK_EQ(rt::crc32("6789", rt::crc32("12345")), 0xCBF43926u);
    CHECK_EQ(rt::adler32("Wikipedia"), 0x11E60398u);
    CHECK_EQ(rt::adler32(""), 1u);
    CHECK_EQ(rt::adler32("pedia", rt::adler32("Wiki")), 0x11E60398u);
    // Past the 5552-byte blocks where the sums are reduced: against the definition.
    const std::string big = random_bytes(100000, 1);
    std::uint64_t a = 1, b = 0;
    for (const char c : big) {
        a = (a + static_cast<unsigned char>(c)) % 65521;
        b = (b + a) % 65521;
    }
    CHECK_EQ(rt::adler32(big), static_cast<std::uint32_t>(b << 16 | a));
}

TEST(huffman_code_lengths_are_limited_complete_and_optimal) {
    // Fibonacci frequencies make an unlimited Huffman code as deep as there are symbols.
    std::vector<std::uint32_t> fib = {1, 1};
    while (fib.size() < 30) fib.push_back(fib[fib.size() - 1] + fib[fib.size() - 2]);
    for (const int limit : {7, 15}) {
        const auto lengths = rt::huffman_code_lengths(fib, limit);
        double kraft = 0;
        for (const auto l : lengths) {
            CHECK(l >= 1 && l <= limit);
            kraft += std::ldexp(1.0, -l);
        }
        CHECK_EQ(kraft, 1.0);  // complete: zlib's decoder refuses anything else
    }
    // Without a binding limit: Huffman's lengths. {1, 1, 2, 4}: 3, 3, 2, 1.
    const auto small = rt::huffman_code_lengths({1, 1, 2, 4, 0}, 15);
    CHECK(small == std::vector<std::uint8_t>({3, 3, 2, 1, 0}));
    // With a limit of 2 the best is all 2.
    CHECK(rt::huffman_code_lengths({1, 1, 2, 4}, 2) == std::vector<std::uint8_t>({2, 2, 2, 2}));
    CHECK(rt::huffman_code_lengths({0, 5, 0}, 15) == std::vector<std::uint8_t>({0, 1, 0}));
    CHECK(rt::huffman_code_lengths({0, 0}, 15) == std::vector<std::uint8_t>({0, 0}));
}

TEST(deflate_hand_checked_streams) {
    // An empty final fixed block: 1, 01, then the 7-bit end-of-block code 0000000.
    CHECK(rt::deflate("") == "\x03\x00"sv);
    // "a": 1, 01, literal 0x61 as the 8-bit code 0x30 + 0x61, end of block (zlib's bytes too).
    CHECK(rt::deflate("a") == "\x4b\x04\x00"sv);
    CHECK(rt::inflate("\x4b\x04\x00"sv, 10) == "a");
    // A stored block: 1, 00, padding, LEN 5, NLEN, the bytes.
    CHECK(rt::inflate("\x01\x05\x00\xfa\xff"
                      "hello"sv,
                      10) == "hello");
    // zlib -9's stream (a fixed block with back-references) of this text.
    const std::string_view zlib9 =
        "\xcb\x48\xcd\xc9\xc9\x57\xc8\xc0\x20\xcb\xf3\x8b\x72\x52\x74\x90\x39\x8a\x00"sv;
    std::size_t used = 0;
    CHECK(rt::inflate(zlib9, 100, &used) == "hello hello hello hello world, hello world!");
    CHECK_EQ(used, zlib9.size());
    CHECK(rt::zlib_decompress("\x78\x9c\x4b\x4c\x4a\x06\x00\x02\x4d\x01\x27"sv, 10) == "abc");
    CHECK(rt::zlib_compress("abc").substr(0, 2) == "\x78\x9c"sv);
}

TEST(deflate_round_trips) {
    check_round_trip("");
    check_round_trip("x");
    check_round_trip(std::string(100000, 'a'));  // one long run: matches overlapping themselves
    check_round_trip(random_bytes(200000, 2));   // incompressible: stored blocks
    check_round_trip(random_bytes(300000, 3, 4));
    std::string text;
    for (int i = 0; i < 20000; ++i) text += "line " + std::to_string(i % 937) + " of the text\n";
    check_round_trip(text);
    // Skewed symbols (Fibonacci counts) at random places: codes that must be length-limited.
    std::string skewed;
    std::uint32_t f0 = 1, f1 = 1;
    for (int symbol = 0; symbol < 26; ++symbol) {
        skewed.append(f0, static_cast<char>(symbol * 7));
        const std::uint32_t next = f0 + f1;
        f0 = f1;
        f1 = next;
    }
    Random random(4);
    for (std::size_t i = skewed.size() - 1; i > 0; --i)
        std::swap(skewed[i], skewed[random.next() % (i + 1)]);
    check_round_trip(skewed);
    // Mixed: a large input whose blocks choose differently.
    std::string mixed = random_bytes(70000, 5) + std::string(70000, 'z') + text.substr(0, 70000) +
                        random_bytes(70000, 6, 3);
    check_round_trip(mixed);
    // Compression is real: text and runs shrink a lot.
    CHECK(rt::deflate(text).size() * 10 < text.size());
    CHECK(rt::deflate(std::string(100000, 'a')).size() < 300);
    CHECK(rt::deflate(random_bytes(200000, 2)).size() < 200000 + 200000 / 1000 + 20);
}

TEST(inflate_rejects_malformed_streams) {
    CHECK(throws_error([] { rt::inflate("\x07"sv, 10); }));      // block type 3
    CHECK(throws_error([] { rt::inflate("\x4b\x04"sv, 10); }));  // ends early
    CHECK(throws_error([] { rt::inflate(""sv, 10); }));          // nothing at all
    CHECK(throws_error([] {
        rt::inflate(
            "\x01\x05\x00\xfa\xfe"
            "hello"sv,
            10);
    }));  // NLEN is not ~LEN
    CHECK(throws_error([] { rt::inflate(rt::deflate(std::string(100, 'a')), 99); }));  // too big
    // A fixed-block match of distance 1 before any output: 1, 01, length code 257, distance 0.
    CHECK(throws_error([] { rt::inflate("\x03\x02"sv, 10); }));
    std::string z = rt::zlib_compress("some data");
    z.back() = static_cast<char>(z.back() ^ 1);
    CHECK(throws_error([&] { rt::zlib_decompress(z, 100); }));  // wrong Adler-32
    CHECK(throws_error([] { rt::zlib_decompress("\x78\x9d\x03\x00\x00\x00\x00\x01"sv, 10); }));
}

TEST(ppm_8_bit_is_the_original_format) {
    const rt::Raster r = raster_of(2, 1, {0, 0.5, 1, -1, 2, NAN});
    const std::string plain = rt::encode_image(r, {});
    CHECK(plain == "P6\n2 1\n255\n\x00\x80\xff\x00\xff\x00"sv);  // round(127.5) = 128
    // Metadata goes in comment lines after the magic number; the pixels stay.
    rt::ImageEncoding e;
    e.metadata.set("Software", "rt test");
    e.metadata.set("Scene", "a b.in");
    const std::string commented = rt::encode_image(r, e);
    CHECK(commented ==
          "P6\n# Software: rt test\n# Scene: a b.in\n2 1\n255\n\x00\x80\xff\x00\xff\x00"sv);
    // rt reads its own output back as a texture, comments and all.
    const fs::path dir = work_dir("image_io_ppm");
    write_file(dir / "c.ppm", commented);
    const rt::Image image = rt::read_texture(dir / "c.ppm");
    CHECK_EQ(image.width, 2);
    CHECK_EQ(image.values[1], 128 / 255.0f);
    CHECK_EQ(image.values[2], 1.0f);
}

TEST(ppm_16_bit_by_hand) {
    const rt::Raster r = raster_of(2, 1, {0.5, 1, -1, 0.25, 2, NAN});
    rt::ImageEncoding e;
    e.bits = 16;
    // 65535 / 2 = 32767.5 rounds to 32768; 65535 / 4 = 16383.75 to 16384; big-endian.
    CHECK(rt::encode_image(r, e) ==
          "P6\n2 1\n65535\n\x80\x00\xff\xff\x00\x00\x40\x00\xff\xff\x00\x00"sv);
    const fs::path dir = work_dir("image_io_ppm16");
    write_file(dir / "d.ppm", rt::encode_image(r, e));
    CHECK_EQ(rt::read_texture(dir / "d.ppm").values[0], static_cast<float>(32768 / 65535.0));
}

TEST(pfm_holds_the_raw_values_bottom_row_first) {
    const rt::Raster r = raster_of(2, 2,
                                   {0.5, -1.25, 3, 0, 1, 2,  // top row
                                    0.25, 100, -0, 7, 8, 9});
    rt::ImageEncoding e;
    e.format = rt::ImageFormat::pfm;
    e.gamma = {rt::Gamma::Kind::srgb, 1};  // ignored: PFM is linear
    e.bits = 16;                           // ignored too
    const std::string pfm = rt::encode_image(r, e);
    const std::string header = "PF\n2 2\n-1.0\n";
    CHECK_EQ(pfm.substr(0, header.size()), header);
    CHECK_EQ(pfm.size(), header.size() + 2 * 2 * 3 * 4);
    auto value = [&](std::size_t i) {
        std::uint32_t bits = 0;
        for (std::size_t b = 0; b < 4; ++b)
            bits |= std::uint32_t{static_cast<unsigned char>(pfm[header.size() + 4 * i + b])}
                    << (8 * b);
        return std::bit_cast<float>(bits);
    };
    const float expected[] = {0.25f, 100, -0.0f, 7, 8, 9, 0.5f, -1.25f, 3, 0, 1, 2};
    for (std::size_t i = 0; i < 12; ++i) CHECK_EQ(value(i), expected[i]);
    // Little-endian: 0.25f is 0x3E800000.
    CHECK(pfm.substr(header.size(), 4) == "\x00\x00\x80\x3e"sv);
}

TEST(gamma_values_by_hand) {
    const rt::Gamma srgb{rt::Gamma::Kind::srgb, 1};
    CHECK_EQ(rt::encode_gamma(0, srgb), 0.0);
    CHECK_NEAR(rt::encode_gamma(0.0031308, srgb), 0.040449936, 1e-9);  // 12.92 · 0.0031308
    CHECK_NEAR(rt::encode_gamma(0.0031309, srgb), 0.040451, 1e-6);     // the curve continues
    CHECK_NEAR(rt::encode_gamma(0.5, srgb), 0.7353569831, 1e-9);  // 1.055 · 0.5^(1/2.4) − 0.055
    CHECK_NEAR(rt::encode_gamma(1, srgb), 1.0, 1e-12);
    const rt::Gamma g22{rt::Gamma::Kind::power, 2.2};
    CHECK_NEAR(rt::encode_gamma(0.5, g22), 0.7297400528, 1e-9);  // 0.5^(1/2.2)
    // Quantized: 255 · 0.73536 = 187.52 -> 188; 255 · 0.72974 = 186.08 -> 186; clamping first.
    const rt::Raster r = raster_of(1, 1, {0.5, 2, -1});
    CHECK(rt::quantize(r, 8, srgb).bytes == std::vector<std::uint8_t>({188, 255, 0}));
    CHECK(rt::quantize(r, 8, g22).bytes == std::vector<std::uint8_t>({186, 255, 0}));
    CHECK(rt::quantize(r, 8, {}).bytes == std::vector<std::uint8_t>({128, 255, 0}));
    // 65535 · 0.7353569831 = 48191.62 -> 48192 = 0xBC40.
    CHECK(rt::quantize(r, 16, srgb).bytes ==
          std::vector<std::uint8_t>({0xBC, 0x40, 0xFF, 0xFF, 0, 0}));

    CHECK(rt::parse_gamma("srgb") == srgb);
    CHECK(rt::parse_gamma("sRGB") == srgb);
    CHECK(rt::parse_gamma("linear") == rt::Gamma{});
    CHECK(rt::parse_gamma("1") == rt::Gamma{});
    CHECK(rt::parse_gamma("2.2") == g22);
    for (const char* bad : {"0", "-1", "nan", "inf", "x", "", "2.2x", "1e400"})
        CHECK(!rt::parse_gamma(bad));
    CHECK_EQ(rt::gamma_name(g22), std::string("2.2"));
    CHECK_EQ(rt::gamma_name(srgb), std::string("srgb"));
}

TEST(format_names_and_extensions) {
    using F = rt::ImageFormat;
    CHECK(rt::format_from_extension("out.png") == F::png);
    CHECK(rt::format_from_extension("OUT.PNG") == F::png);
    CHECK(rt::format_from_extension("a/b.c/x.Pfm") == F::pfm);
    CHECK(rt::format_from_extension("x.ppm") == F::ppm);
    bool has = true;
    CHECK(!rt::format_from_extension("dir.png/out", &has));
    CHECK(!has);
    CHECK(!rt::format_from_extension("x.jpg", &has));
    CHECK(has);
    CHECK(!rt::format_from_extension(".png", &has));  // a hidden file's name, not an extension
    CHECK(!has);
    CHECK(rt::parse_format_name("PNG") == F::png);
    CHECK(!rt::parse_format_name("gif"));
    CHECK_EQ(std::string(rt::format_name(F::pfm)), std::string("pfm"));
}

TEST(png_structure) {
    const rt::Raster r =
        raster_of(3, 2, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1, 0.5, 0.5, 0.5});
    rt::ImageEncoding e;
    e.format = rt::ImageFormat::png;
    e.metadata.set("Software", "rt test");
    e.metadata.set("Scene", "sc\xc3\xa8ne.in");  // UTF-8: an iTXt chunk
    const std::string png = rt::encode_image(r, e);
    CHECK(png.substr(0, 8) == "\x89PNG\r\n\x1a\n"sv);
    // Chunks: each with a correct CRC, in the order IHDR, text, IDAT, IEND.
    std::vector<std::string> types;
    for (std::size_t at = 8; at + 12 <= png.size();) {
        const std::uint32_t length = be32(png, at);
        const std::string type = png.substr(at + 4, 4);
        types.push_back(type);
        CHECK_EQ(be32(png, at + 8 + length),
                 rt::crc32(std::string_view(png).substr(at + 4, 4 + length)));
        if (type == "IHDR") {
            CHECK_EQ(length, 13u);
            CHECK_EQ(be32(png, at + 8), 3u);                            // width
            CHECK_EQ(be32(png, at + 12), 2u);                           // height
            CHECK(png.substr(at + 16, 5) == "\x08\x02\x00\x00\x00"sv);  // 8-bit RGB, no interlace
        }
        if (type == "tEXt") CHECK(png.substr(at + 8, length) == "Software\0rt test"sv);
        if (type == "iTXt") CHECK(png.substr(at + 8, length) == "Scene\0\0\0\0\0sc\xc3\xa8ne.in"sv);
        at += 12 + length;
    }
    CHECK(types == std::vector<std::string>({"IHDR", "tEXt", "iTXt", "IDAT", "IEND"}));
    CHECK(png.substr(png.size() - 12) == "\0\0\0\0IEND\xae\x42\x60\x82"sv);
    const rt::DecodedImage d = rt::decode_png(png);
    CHECK_EQ(d.image.width, 3);
    CHECK_EQ(d.image.height, 2);
    CHECK(d.image.bytes == rt::quantize(r, 8, {}).bytes);
    CHECK(d.metadata.entries == e.metadata.entries);
}

TEST(png_round_trips) {
    const rt::Raster r = busy_raster(301, 203);
    for (const int bits : {8, 16})
        for (const rt::Gamma gamma : {rt::Gamma{}, rt::Gamma{rt::Gamma::Kind::srgb, 1}}) {
            const rt::SampleImage samples = rt::quantize(r, bits, gamma);
            const rt::DecodedImage d = rt::decode_png(rt::encode_png(samples, {}));
            CHECK_EQ(d.image.bits, bits);
            CHECK_EQ(d.image.channels, 3);
            CHECK(d.image.bytes == samples.bytes);
        }
    // Grey, grey and alpha, RGB and alpha.
    for (const int channels : {1, 2, 4}) {
        rt::SampleImage s;
        s.width = 17;
        s.height = 5;
        s.channels = channels;
        s.bits = channels == 2 ? 16 : 8;
        s.bytes.resize(s.row_bytes() * 5);
        Random random(static_cast<std::uint64_t>(channels));
        for (auto& b : s.bytes) b = static_cast<std::uint8_t>(random.next() % 7 * 40);
        const rt::DecodedImage d = rt::decode_png(rt::encode_png(s, {}));
        CHECK_EQ(d.image.channels, channels);
        CHECK(d.image.bytes == s.bytes);
    }
    // The sample accessor reads 16-bit samples big-endian.
    const rt::SampleImage s16 = rt::quantize(raster_of(1, 1, {0.5, 0, 1}), 16, {});
    CHECK_EQ(s16.sample(0, 0, 0), 32768u);
    CHECK_EQ(s16.sample(0, 0, 2), 65535u);
}

TEST(png_decodes_files_another_encoder_wrote) {
    // Made with Python's zlib (levels 1, 9 and 0) by a script; expected pixels by hand.
    const std::string_view grey2 =
        "\x89\x50\x4e\x47\x0d\x0a\x1a\x0a\x00\x00\x00\x0d\x49\x48\x44\x52\x00\x00\x00\x05\x00\x00"
        "\x00\x02\x02\x00\x00\x00\x00\xff\xb1\x51\x20\x00\x00\x00\x0e\x49\x44\x41\x54\x78\x01\x63"
        "\x90\x76\x60\x78\xd2\x00\x00\x03\xd5\x01\xc0\xf2\x06\x7f\x6d\x00\x00\x00\x00\x49\x45\x4e"
        "\x44\xae\x42\x60\x82"sv;
    rt::DecodedImage d = rt::decode_png(grey2);  // 2-bit grey, 5 x 2: 0 1 2 3 1 / 3 2 1 0 2
    CHECK_EQ(d.image.channels, 1);
    CHECK(d.image.bytes == std::vector<std::uint8_t>({0, 85, 170, 255, 85, 255, 170, 85, 0, 170}));

    const std::string_view palette4 =
        "\x89\x50\x4e\x47\x0d\x0a\x1a\x0a\x00\x00\x00\x0d\x49\x48\x44\x52\x00\x00\x00\x03\x00\x00"
        "\x00\x02\x04\x03\x00\x00\x00\x6f\x5a\x7b\x29\x00\x00\x00\x09\x50\x4c\x54\x45\xff\x00\x00"
        "\x00\xff\x00\x00\x00\xff\x2d\x4a\xcd\x8a\x00\x00\x00\x02\x74\x52\x4e\x53\x80\x00\x4d\x10"
        "\x55\x73\x00\x00\x00\x16\x74\x45\x58\x74\x43\x6f\x6d\x6d\x65\x6e\x74\x00\x6d\x61\x64\x65"
        "\x20\x62\x79\x20\x70\x79\x74\x68\x6f\x6e\x99\x33\x93\xa3\x00\x00\x00\x0e\x49\x44\x41\x54"
        "\x78\xda\x63\x60\x54\x60\x50\x62\x00\x00\x00\xcf\x00\x44\x84\x68\xaf\x5a\x00\x00\x00\x00"
        "\x49\x45\x4e\x44\xae\x42\x60\x82"sv;
    d = rt::decode_png(palette4);  // 4-bit palette red, green, blue; red half transparent
    CHECK_EQ(d.image.channels, 4);
    CHECK(d.image.bytes ==
          std::vector<std::uint8_t>({255, 0, 0,   128, 0, 255, 0,   0,   0,   0, 255, 255,
                                     0,   0, 255, 255, 0, 0,   255, 255, 255, 0, 0,   128}));
    CHECK(*d.metadata.find("Comment") == "made by python");

    const std::string_view interlaced =
        "\x89\x50\x4e\x47\x0d\x0a\x1a\x0a\x00\x00\x00\x0d\x49\x48\x44\x52\x00\x00\x00\x03\x00\x00"
        "\x00\x03\x08\x02\x00\x00\x01\xae\x4d\x12\x7e\x00\x00\x00\x2c\x49\x44\x41\x54\x78\x01\x01"
        "\x21\x00\xde\xff\x00\x01\x02\x03\x00\x15\x02\x11\x00\x01\x2a\x11\x15\x2a\x1f\x00\x0b\x02"
        "\x0a\x00\x0b\x2a\x18\x00\x01\x16\x0a\x0b\x16\x11\x15\x16\x18\x19\x2d\x01\xc3\x8a\x4e\x52"
        "\x9d\x00\x00\x00\x00\x49\x45\x4e\x44\xae\x42\x60\x82"sv;
    d = rt::decode_png(interlaced);  // Adam7, 3 x 3 RGB: (10x + 1, 20y + 2, 7(x + y) + 3)
    CHECK_EQ(d.image.channels, 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) {
            CHECK_EQ(d.image.sample(x, y, 0), unsigned(10 * x + 1));
            CHECK_EQ(d.image.sample(x, y, 1), unsigned(20 * y + 2));
            CHECK_EQ(d.image.sample(x, y, 2), unsigned(7 * (x + y) + 3));
        }

    // Damage is reported, never read past.
    std::string bad_crc(grey2);
    bad_crc[20] ^= 1;
    CHECK(throws_error([&] { rt::decode_png(bad_crc); }));
    CHECK(throws_error([&] { rt::decode_png(grey2.substr(0, grey2.size() - 12)); }));  // no IEND
    CHECK(throws_error([&] { rt::decode_png(grey2.substr(0, 40)); }));
    CHECK(throws_error([] { rt::decode_png("P6\n1 1\n255\n\0\0\0"sv); }));
}

TEST(damaged_streams_and_files_fail_cleanly) {
    // Every damage is either reported as rt::Error or decodes to something; none reads out
    // of bounds (the sanitizer builds check that part).
    const std::string data = random_bytes(5000, 8, 5) + std::string(3000, 'q');
    const std::string packed = rt::zlib_compress(data);
    const std::string png = rt::encode_png(rt::quantize(busy_raster(40, 30), 8, {}), {});
    Random random(9);
    int failures = 0;
    for (int round = 0; round < 300; ++round) {
        std::string z = packed;
        std::string p = png;
        for (int flips = 0; flips < 3; ++flips) {
            z[random.next() % z.size()] ^= static_cast<char>(1 << (random.next() % 8));
            p[8 + random.next() % (p.size() - 8)] ^= static_cast<char>(1 << (random.next() % 8));
        }
        failures += throws_error([&] { rt::zlib_decompress(z, data.size()); });
        failures += throws_error(
            [&] { rt::zlib_decompress(z.substr(0, random.next() % z.size()), 1 << 20); });
        failures += throws_error([&] { rt::decode_png(p); });
        failures += throws_error([&] { rt::inflate(random_bytes(64, random.next()), 1 << 16); });
    }
    CHECK(failures > 600);  // most damage is caught (by the checksums where nothing else)
}

TEST(quantize_rounds_as_lround_does_at_every_half_and_beside_it) {
    bool same = true;
    const auto agree = [&](double x) {
        same = same && rt::round_to_nearest(x) == static_cast<unsigned>(std::lround(x));
    };
    for (unsigned k = 0; k <= 65536; ++k) {
        for (const double x : {k + 0.0, k + 0.5}) {
            agree(x);
            agree(std::nextafter(x, 0.0));
            agree(std::nextafter(x, 1e9));
        }
    }
    std::uint64_t state = 12345;
    for (int i = 0; i < 200000; ++i) {
        state = state * 6364136223846793005u + 1442695040888963407u;
        agree(static_cast<double>(state >> 11) * 0x1p-53 * 65535.0);
    }
    agree(0.49999999999999994);  // where x + 0.5 would round up to 1
    CHECK(same);
}

TEST(linear_samples_are_the_clamped_component_rounded_as_lround_does) {
    // The linear path works four components at a time, the rest one by one: every kind of
    // component (below 0, above 1, NaN, infinities, every sample's value and half-way point
    // and their neighbours) at every place, against the definition.
    std::vector<double> values = {-1,
                                  -0.0,
                                  0.0,
                                  1,
                                  2,
                                  NAN,
                                  -NAN,
                                  INFINITY,
                                  -INFINITY,
                                  1e300,
                                  -1e-300,
                                  0x1p-1074,
                                  std::nextafter(1.0, 2.0)};
    for (const double max : {255.0, 65535.0})
        for (int k = 0; k <= 255; ++k)
            for (const double at : {k / 255.0 * (max / 255), (k + 0.5) / max * (max / 255)})
                for (const double x : {at, std::nextafter(at, 0.0), std::nextafter(at, 2.0)})
                    values.push_back(x * 255 / max);
    std::uint64_t state = 7;
    while (values.size() % 3 != 0 || values.size() < 5000) {
        state = state * 6364136223846793005u + 1442695040888963407u;
        values.push_back(static_cast<double>(state >> 11) * 0x1p-53 * 1.4 - 0.2);
    }
    const int width = static_cast<int>(values.size() / 3);
    for (const int bits : {8, 16}) {
        const double max = bits == 16 ? 65535 : 255;
        const std::vector<std::uint8_t> got =
            rt::quantize(raster_of(width, 1, values), bits, {}).bytes;
        bool same = true;
        for (std::size_t i = 0; i < values.size(); ++i) {
            const double c = std::isnan(values[i]) ? 0 : std::clamp(values[i], 0.0, 1.0);
            const auto want = static_cast<unsigned>(std::lround(max * c));
            const unsigned have = bits == 16 ? unsigned{got[2 * i]} << 8 | got[2 * i + 1] : got[i];
            same = same && have == want;
        }
        CHECK(same);
    }
}

TEST(an_image_in_pieces_is_the_whole_file) {
    // 1000 x 70 is 210,000 bytes of 8-bit samples: the header and four runs of rows; the
    // pieces joined are the file encode_image gives, in every format.
    std::vector<double> values;
    for (int i = 0; i < 1000 * 70 * 3; ++i) values.push_back((i % 1013) / 1000.0);
    const rt::Raster r = raster_of(1000, 70, values);
    for (const rt::ImageFormat format :
         {rt::ImageFormat::ppm, rt::ImageFormat::png, rt::ImageFormat::pfm})
        for (const int bits : {8, 16}) {
            rt::ImageEncoding e;
            e.format = format;
            e.bits = bits;
            e.metadata.set("Software", "rt test");
            const auto [joined, pieces] =
                joined_pieces([&](const auto& sink) { rt::encode_image_in_pieces(r, e, sink); });
            CHECK(joined == rt::encode_image(r, e));
            CHECK_EQ(pieces, format == rt::ImageFormat::ppm ? (bits == 8 ? 4 : 7) : 1);
        }
}

namespace {

// Values that every quantizer must agree on: halves and what lies beside them, the ends of
// the range and beyond, NaN and infinities, and noise.
std::vector<double> awkward_values(std::size_t count, std::uint64_t seed) {
    Random random(seed);
    const double specials[] = {0.5 / 255, 127.5 / 255, 0.5 / 65535, 0,        1,         -0.0,
                               -1e-300,   1 + 1e-16,   NAN,         INFINITY, -INFINITY, 1e300};
    std::vector<double> values;
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint64_t pick = random.next() % 4;
        if (pick == 0) {
            values.push_back(specials[random.next() % std::size(specials)]);
        } else if (pick == 1) {
            // A half of a step of 255 or 65535, or the double beside it.
            const double max = random.next() % 2 == 0 ? 255 : 65535;
            const double half =
                (static_cast<double>(random.next() % static_cast<unsigned>(max)) + 0.5) / max;
            const int side = static_cast<int>(random.next() % 3) - 1;
            values.push_back(side == 0 ? half : std::nextafter(half, side * 2.0));
        } else {
            values.push_back(1.2 * random.uniform() - 0.1);
        }
    }
    return values;
}

const rt::Gamma kGammas[] = {{}, {rt::Gamma::Kind::srgb, 1}, {rt::Gamma::Kind::power, 2.2}};

}  // namespace

// The render quantizes each row on its own, starting anywhere in a run of four: every slice
// gives the samples the whole does there.
TEST(quantized_values_of_any_slice_are_those_of_the_whole) {
    const std::vector<double> values = awkward_values(3 * 97, 11);
    for (const int bits : {8, 16})
        for (const rt::Gamma& gamma : kGammas) {
            const std::size_t width = static_cast<std::size_t>(bits / 8);
            std::vector<std::uint8_t> whole(values.size() * width);
            rt::quantize_values(values, bits, gamma, whole.data());
            for (std::size_t begin = 0; begin < 9; ++begin)
                for (const std::size_t end :
                     {begin, begin + 1, begin + 5, values.size() - 3, values.size()}) {
                    std::vector<std::uint8_t> part((end - begin) * width);
                    rt::quantize_values(std::span(values).subspan(begin, end - begin), bits, gamma,
                                        part.data());
                    CHECK(std::equal(part.begin(), part.end(),
                                     whole.begin() + static_cast<std::ptrdiff_t>(begin * width)));
                }
        }
}

// A render kept as samples is written as the file its raster would have made, in pieces or
// whole, PPM and PNG, any bits and gamma, metadata and all.
TEST(samples_are_written_as_the_raster_they_came_from) {
    const int width = 700, height = 41;  // 86,100 samples: a PPM in several pieces
    const std::vector<double> values = awkward_values(3u * width * height, 12);
    const rt::Raster r = raster_of(width, height, values);
    for (const rt::ImageFormat format : {rt::ImageFormat::ppm, rt::ImageFormat::png})
        for (const int bits : {8, 16})
            for (const rt::Gamma& gamma : kGammas) {
                rt::ImageEncoding e;
                e.format = format;
                e.bits = bits;
                e.gamma = gamma;
                e.metadata.set("Software", "rt test");
                const rt::SampleRaster samples = rt::quantize_raster(r, bits, gamma);
                CHECK(std::equal(samples.bytes().begin(), samples.bytes().end(),
                                 rt::quantize(r, bits, gamma).bytes.begin()));
                const auto [joined, pieces] = joined_pieces(
                    [&](const auto& sink) { rt::encode_samples_in_pieces(samples, e, sink); });
                CHECK(joined == rt::encode_image(r, e));
                CHECK(format == rt::ImageFormat::png ? pieces == 1 : pieces > 2);
            }
    // Samples of other bits or gamma, or PFM, which stores floats, are refused.
    const rt::SampleRaster samples = rt::quantize_raster(r, 8, {});
    const auto refused = [&](const rt::ImageEncoding& e) {
        try {
            rt::encode_samples_in_pieces(samples, e, [](std::string_view) {});
        } catch (const std::invalid_argument&) {
            return true;
        }
        return false;
    };
    rt::ImageEncoding e;
    CHECK(!refused(e));
    e.bits = 16;
    CHECK(refused(e));
    e.bits = 8;
    e.gamma = kGammas[1];
    CHECK(refused(e));
    e.gamma = {};
    e.format = rt::ImageFormat::pfm;
    CHECK(refused(e));
    CHECK(throws_error([] { rt::SampleRaster(2, 2, 12, {}); }));
}

TEST(a_new_raster_is_black_small_or_large) {
    // A large raster's pages come zeroed from the kernel and are not written first.
    for (const int side : {3, 1024}) {
        const rt::Raster r(side, side);
        const auto v = r.values();
        CHECK(
            std::all_of(v.begin(), v.end(), [](double x) { return x == 0.0 && !std::signbit(x); }));
    }
}

TEST(ppm_from_the_raster_is_the_header_and_quantize_samples) {
    // encode_image quantizes straight into the file's bytes; encode_ppm of quantize is the
    // same file, for both depths, with metadata and with a gamma.
    std::vector<double> values;
    std::uint64_t state = 99;
    for (int i = 0; i < 37 * 23 * 3; ++i) {
        state = state * 6364136223846793005u + 1442695040888963407u;
        values.push_back(static_cast<double>(state >> 11) * 0x1p-53 * 1.4 - 0.2);
    }
    const rt::Raster r = raster_of(37, 23, values);
    for (const int bits : {8, 16}) {
        rt::ImageEncoding e;
        e.bits = bits;
        e.metadata.set("Software", "rt test");
        CHECK(rt::encode_image(r, e) == rt::encode_ppm(rt::quantize(r, bits, {}), e.metadata));
        e.gamma.kind = rt::Gamma::Kind::srgb;
        CHECK(rt::encode_image(r, e) == rt::encode_ppm(rt::quantize(r, bits, e.gamma), e.metadata));
    }
}
