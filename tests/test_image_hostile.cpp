// The image library and rtimg against the hostile files of issue 21's campaign: text chunks
// that inject header lines, keywords the PNG specification does not allow, NULs, a flood of
// records, text that unpacks to gigabytes, NaN in a comparison, odd PFM scales, a full size
// that claims gigabytes, and messages that show what they quote escaped.
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>

#include "check.h"
#include "cli_util.h"
#include "image/deflate.h"
#include "rt/image_merge.h"
#include "rt/error.h"
#include "rt/image_compare.h"
#include "rt/image_file.h"
#include "rt/image_io.h"
#include "rt/image_merge.h"

namespace fs = std::filesystem;
using namespace std::string_literals;
using namespace std::string_view_literals;
using rt_test::read_file;
using rt_test::run_rtimg;
using rt_test::write_file;

namespace {

void put_u32(std::string& out, std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>(v >> shift));
}

std::string chunk(std::string_view type, std::string_view body) {
    std::string out;
    put_u32(out, static_cast<std::uint32_t>(body.size()));
    out += type;
    out += body;
    put_u32(out, rt::crc32(body, rt::crc32(type)));
    return out;
}

// A 1 x 2 8-bit RGB PNG (red above blue) with `extra` chunks between IHDR and IDAT, each with
// a valid CRC.
std::string png_with(const std::string& extra) {
    std::string header;
    put_u32(header, 1);
    put_u32(header, 2);
    header += "\x08\x02\x00\x00\x00"sv;
    const std::string rows = "\x00\xff\x00\x00\x00\x00\x00\xff"s;
    return "\x89PNG\r\n\x1a\n"s + chunk("IHDR", header) + extra +
           chunk("IDAT", rt::zlib_compress(rows)) + chunk("IEND", "");
}

std::string text_chunk(std::string_view keyword, std::string_view text) {
    std::string body(keyword);
    body.push_back('\0');
    body += text;
    return chunk("tEXt", body);
}

std::string error_of(const auto& f) {
    try {
        f();
    } catch (const rt::Error& e) {
        return e.what();
    }
    return "";
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A w x h PFM (little-endian) with every value v.
std::string pfm(int w, int h, float v) {
    std::string out = "PF\n" + std::to_string(w) + " " + std::to_string(h) + "\n-1.0\n";
    for (int i = 0; i < 3 * w * h; ++i) {
        char bytes[4];
        std::memcpy(bytes, &v, 4);
        out.append(bytes, 4);
    }
    return out;
}

}  // namespace

TEST(a_png_keyword_must_be_one_the_specification_allows) {
    // Finding 4: a keyword holding a newline became PPM header lines: "1 1\n255\n" and a
    // pixel made a valid 1x1 image of another colour.
    const std::string inject = png_with(text_chunk("A\n1 1\n255\n\x01\x02\x03\n#", "x"));
    CHECK_CONTAINS(error_of([&] { rt::decode_png(inject); }),
                   "PNG tEXt chunk has an invalid keyword 'A\\x0a1 1\\x0a255");
    for (const std::string_view bad : {""sv, " lead"sv, "trail "sv, "two  spaces"sv, "tab\there"sv,
                                       "del\x7f"sv, "c1\x85"sv, "nbsp\xa0"sv})
        CHECK_CONTAINS(error_of([&] { rt::decode_png(png_with(text_chunk(bad, "v"))); }),
                       "invalid keyword");
    CHECK_CONTAINS(
        error_of([&] { rt::decode_png(png_with(text_chunk(std::string(80, 'k'), "v"))); }),
        "invalid keyword");
    // 79 characters, single spaces and Latin-1 letters are a keyword.
    const std::string k79(79, 'k');
    CHECK(rt::decode_png(png_with(text_chunk(k79, "v"))).metadata.find(k79) != nullptr);
    CHECK(*rt::decode_png(png_with(text_chunk("Creation Time", "now")))
               .metadata.find("Creation Time") == "now");
    // The same rule on writing, for the key as UTF-8 (so "\xc2\xa0", U+00A0, is refused too).
    for (const std::string_view bad :
         {"a\nb"sv, " x"sv, "x  y"sv, "\xc2\xa0"sv, "\xc4\x80"sv, "\xff"sv})
        CHECK_CONTAINS(error_of([&] {
                           rt::ImageMetadata m;
                           m.set(bad, "v");
                           rt::encode_png(rt::SampleImage{1, 1, 3, 8, {0, 0, 0}}, m);
                       }),
                       "cannot be a PNG text keyword");
}

TEST(keys_and_values_cannot_inject_ppm_header_lines) {
    rt::ImageMetadata m;
    m.set("Key\n1 1", "v");
    const rt::SampleImage tall{1, 2, 3, 8, {255, 0, 0, 0, 0, 255}};
    CHECK_CONTAINS(error_of([&] { rt::encode_ppm(tall, m); }),
                   "'Key\\x0a1 1' cannot be a PPM metadata key");
    CHECK_CONTAINS(error_of([&] { rt::encode_ppm_plain(tall, m); }),
                   "cannot be a PPM metadata key");
    m.entries.clear();
    m.set("Creation Time", "v");  // a PNG keyword, but it would not read back from a PPM
    CHECK_CONTAINS(error_of([&] { rt::encode_ppm(tall, m); }), "cannot be a PPM metadata key");
    // A value with a line end (or a carriage return alone, at its end too) is refused, not
    // changed; everything else in a value reads back as it was.
    for (const std::string value : {"a\n1 1\n255\n...", "a\rb", "ab\r"}) {
        m.entries.clear();
        m.set("Note", value);
        CHECK_CONTAINS(error_of([&] { rt::encode_ppm(tall, m); }),
                       "the value of PPM metadata key 'Note' holds a line break");
        CHECK_CONTAINS(error_of([&] { rt::encode_ppm_plain(tall, m); }), "holds a line break");
    }
    m.entries.clear();
    m.set("Note", " a: b\t# c \x01\xe9 ");
    for (const std::string& file : {rt::encode_ppm(tall, m), rt::encode_ppm_plain(tall, m)}) {
        const rt::ImageFile back = rt::decode_ppm(file);
        CHECK_EQ(back.width(), 1);
        CHECK_EQ(back.height(), 2);
        CHECK(back.samples.bytes == tall.bytes);
        CHECK(back.metadata.entries == m.entries);
    }
    // A comment whose key has a control character is a comment, not metadata.
    const rt::ImageFile plain = rt::decode_ppm("P6\n# a\x01: b\n1 1\n255\n\0\0\0"sv);
    CHECK(plain.metadata.entries.empty());
    // Through rtimg: the PNG of finding 4 is refused, and so is converting a key with a space.
    const fs::path dir = rt_test::work_dir("image-hostile-inject");
    write_file(dir / "inject.png", png_with(text_chunk("A\n1 1\n255\n\x01\x02\x03\n#", "x")));
    const rt_test::RunResult r = run_rtimg(dir, "convert inject.png out.ppm");
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "rtimg: inject.png: PNG tEXt chunk has an invalid keyword");
    CHECK(!fs::exists(dir / "out.ppm"));
    write_file(dir / "spaced.png", png_with(text_chunk("Creation Time", "now")));
    const rt_test::RunResult s = run_rtimg(dir, "convert spaced.png out.ppm");
    CHECK_EQ(s.status, 1);
    CHECK_CONTAINS(s.err, "'Creation Time' cannot be a PPM metadata key");
    CHECK_EQ(run_rtimg(dir, "convert spaced.png out.png").status, 0);
}

TEST(latin1_keywords_round_trip_png_to_png) {
    // Finding 7: "Café" came back as "CafÃ©" and the next conversion failed.
    rt::ImageMetadata m;
    m.set("Caf\xc3\xa9", "cr\xc3\xa8me");
    m.set("\xc3\x80 \xc3\xbf", "ascii");
    const rt::SampleImage pixel{1, 1, 3, 8, {1, 2, 3}};
    std::string file = rt::encode_png(pixel, m);
    CHECK(file.find("Caf\xe9\0"sv) != std::string::npos);  // Latin-1 in the file
    for (int pass = 0; pass < 3; ++pass) {
        const rt::DecodedImage back = rt::decode_png(file);
        CHECK(back.metadata.entries == m.entries);
        file = rt::encode_png(back.image, back.metadata);
    }
    // Through rtimg, twice.
    const fs::path dir = rt_test::work_dir("image-hostile-latin1");
    write_file(dir / "a.png", png_with(text_chunk("Caf\xe9", "x")));
    CHECK_EQ(run_rtimg(dir, "convert a.png b.png").status, 0);
    CHECK_EQ(run_rtimg(dir, "convert b.png c.png").status, 0);
    const rt_test::RunResult info = run_rtimg(dir, "info c.png");
    CHECK_CONTAINS(info.out, "Caf\xc3\xa9: x\n");
}

TEST(a_nul_in_text_is_refused_never_dropped) {
    // Finding 8: the NUL was accepted on reading and silently dropped on writing.
    CHECK_CONTAINS(error_of([&] { rt::decode_png(png_with(text_chunk("Key", "a\0b"sv))); }),
                   "PNG tEXt chunk 'Key' has a NUL character in its text");
    std::string z = "Key"s + '\0' + '\0' + rt::zlib_compress("a\0b"sv);
    CHECK_CONTAINS(error_of([&] { rt::decode_png(png_with(chunk("zTXt", z))); }),
                   "has a NUL character in its text");
    std::string i = "Key"s + "\0\0\0en\0\0a\0b"s;
    i = "Key"s + '\0' + '\0' + '\0' + "en"s + '\0' + '\0' + "a"s + '\0' + "b"s;
    CHECK_CONTAINS(error_of([&] { rt::decode_png(png_with(chunk("iTXt", i))); }),
                   "has a NUL character in its text");
    rt::ImageMetadata m;
    m.set("Key", "a\0b"s);
    CHECK_CONTAINS(error_of([&] {
                       rt::encode_png(rt::SampleImage{1, 1, 3, 8, {0, 0, 0}}, m);
                   }),
                   "the value of 'Key' holds a NUL character");
    // A PPM comment may hold one; it stays.
    const rt::ImageFile ppm = rt::decode_ppm("P6\n# Key: a\0b\n1 1\n255\n\0\0\0"sv);
    CHECK(*ppm.metadata.find("Key") == "a\0b"s);
}

TEST(metadata_reading_is_bounded_in_records) {
    // Finding 6: 50,000 text chunks took 7 s (200,000 took 71 s); PPM comments likewise.
    std::string many;
    for (std::size_t k = 0; k < rt::ImageMetadata::kMaxEntries; ++k)
        many += text_chunk(rt_test::join('k', k), "v");
    CHECK_EQ(rt::decode_png(png_with(many)).metadata.entries.size(),
             rt::ImageMetadata::kMaxEntries);
    CHECK_CONTAINS(error_of([&] { rt::decode_png(png_with(many + text_chunk("one", "more"))); }),
                   "PNG file has more than 1024 text chunks");
    std::string flood;
    for (int k = 0; k < 200000; ++k) flood += text_chunk(rt_test::join('k', k), "v");
    auto start = std::chrono::steady_clock::now();
    CHECK_CONTAINS(error_of([&] { rt::decode_png(png_with(flood)); }), "more than 1024");
    CHECK(seconds_since(start) < 5);
    std::string ppm = "P6\n";
    for (int k = 0; k < 200000; ++k) ppm += rt_test::join("# k", k, ": v\n");
    ppm += "1 1\n255\n\0\0\0"sv;
    start = std::chrono::steady_clock::now();
    CHECK_CONTAINS(error_of([&] { rt::decode_ppm(ppm); }),
                   "PPM header has more than 1024 metadata comments");
    CHECK(seconds_since(start) < 5);
}

TEST(decompressed_text_is_bounded_in_all) {
    // Finding 14: 64 zTXt chunks of 16 MiB each took 1.1 GB and printed 1 GB. Each chunk
    // alone is within the bound; two together are not.
    const std::string nine = rt::zlib_compress(std::string(9u << 20, 'a'));
    const std::string z = "Big"s + '\0' + '\0' + nine;
    const std::string z2 = "Big2"s + '\0' + '\0' + nine;
    CHECK_EQ(rt::decode_png(png_with(chunk("zTXt", z))).metadata.find("Big")->size(),
             std::size_t{9} << 20);
    const std::string e =
        error_of([&] { rt::decode_png(png_with(chunk("zTXt", z) + chunk("zTXt", z2))); });
    CHECK_CONTAINS(e, "16777216");
}

TEST(a_chunk_type_is_shown_escaped) {
    // Finding 11: type "A\0\x07B" cut the message at the NUL.
    const std::string e = error_of([&] {
        rt::decode_png(
            png_with(chunk("A\0\x07"
                           "B"sv,
                           "x")));
    });
    CHECK_EQ(e, std::string("PNG file has an unknown critical chunk A\\x00\\x07B"));
    std::string bad_crc = png_with(chunk("\x01\x02\x03\x04"sv, "x"));
    bad_crc[8 + 25 + 8] ^= 1;  // the body of the chunk after IHDR
    CHECK_CONTAINS(error_of([&] { rt::decode_png(bad_crc); }),
                   "PNG \\x01\\x02\\x03\\x04 chunk has a wrong CRC");
}

TEST(a_pfm_scale_is_finite_and_not_zero) {
    // Finding 10: "-nan" was accepted and the data read big-endian.
    for (const char* scale : {"-nan", "nan", "inf", "-inf", "0", "-0"}) {
        const std::string file = "PF\n1 1\n"s + scale + "\n" + std::string(12, '\0');
        CHECK_CONTAINS(error_of([&] { rt::decode_pfm(file); }),
                       "PFM scale must be a finite number other than 0");
    }
    const rt::ImageFile ok = rt::decode_pfm(pfm(1, 1, 0.25f));
    CHECK_EQ(ok.floats[0], 0.25f);
}

TEST(nan_is_a_difference_from_any_number) {
    // Finding 5: an all-NaN PFM against an all-zero one passed with "largest difference: 0".
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const rt::ImageFile nans = rt::decode_pfm(pfm(2, 2, nan));
    const rt::ImageFile zeros = rt::decode_pfm(pfm(2, 2, 0));
    const rt::ImageFile infs = rt::decode_pfm(pfm(2, 2, inf));
    rt::ImageDifference d = rt::compare_images(nans, zeros, 1e9);
    CHECK_EQ(d.differing, std::size_t{4});
    CHECK(std::isinf(d.largest));
    CHECK(std::isinf(d.mean_absolute) && std::isinf(d.rms));
    CHECK(std::isinf(d.psnr) && d.psnr < 0);
    // NaN against NaN, and an infinity against itself, are alike.
    d = rt::compare_images(nans, nans, 0);
    CHECK_EQ(d.differing, std::size_t{0});
    CHECK_EQ(d.largest, 0.0);
    CHECK(std::isinf(d.psnr) && d.psnr > 0);
    d = rt::compare_images(infs, infs, 0);
    CHECK_EQ(d.differing, std::size_t{0});
    CHECK_EQ(rt::compare_images(infs, zeros, 0).differing, std::size_t{4});
    // The heat map shows the NaNs at their reddest.
    const rt::SampleImage map = rt::heat_map(nans, zeros, 1);
    CHECK_EQ(map.sample(0, 0, 0), 255u);
    // Finding 9: through rtimg, the worst PSNR is printed as -inf, and the result fails.
    const fs::path dir = rt_test::work_dir("image-hostile-nan");
    write_file(dir / "nan.pfm", pfm(2, 2, nan));
    write_file(dir / "zero.pfm", pfm(2, 2, 0));
    const rt_test::RunResult r = run_rtimg(dir, "diff --tolerance 1000 nan.pfm zero.pfm");
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.out, "largest difference: inf levels\n");
    CHECK_CONTAINS(r.out, "differing pixels: 4 of 4");
    CHECK_CONTAINS(r.out, "PSNR: -inf dB\n");
    CHECK_CONTAINS(r.out, "result: fail");
    const rt_test::RunResult same = run_rtimg(dir, "diff nan.pfm nan.pfm");
    CHECK_EQ(same.status, 0);
    CHECK_CONTAINS(same.out, "PSNR: inf dB\n");
}

TEST(a_recorded_full_size_is_bounded_before_allocating) {
    // Finding 3: a 57-byte PPM claiming 46000x46000 made merge allocate 2 GB for a minute.
    const fs::path dir = rt_test::work_dir("image-hostile-merge");
    write_file(dir / "piece.ppm",
               "P6\n# Region: 0,1,0,1\n# Full-Size: 46000x46000\n1 1\n255\n\0\0\0"s);
    const auto start = std::chrono::steady_clock::now();
    const rt_test::RunResult r = run_rtimg(dir, "merge piece.ppm -o full.ppm");
    CHECK(seconds_since(start) < 5);
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err,
                   "rtimg: piece.ppm records a full size (46000x46000) larger than "
                   "67108864 pixels");
    // The largest allowed full size is still merged (here a gap is found, not allocated far).
    write_file(dir / "edge.ppm",
               "P6\n# Region: 0,1,0,1\n# Full-Size: 8192x8192\n1 1\n255\n\0\0\0"s);
    CHECK_CONTAINS(run_rtimg(dir, "merge edge.ppm -o full.ppm").err,
                   "the pieces leave a gap: 67108863 pixels within columns 0-8191, rows 0-8191 "
                   "of the 8192x8192 image are in no piece");
}

TEST(a_gap_is_found_from_the_pieces_not_from_every_pixel) {
    // Found by fuzz_merge: tiny pieces claiming a large full size took a pixel-by-pixel scan
    // of it (0.9 s and 64 MB for 40 bytes of input); the gap is now found from the pieces'
    // edges. Three pieces of a 7x5 image, leaving two holes: the count and the box are those
    // of the pixels in no piece.
    std::vector<rt::ImagePiece> pieces;
    const auto piece = [&](const char* name, int x0, int y0, int x1, int y1) {
        rt::ImageFile f;
        f.format = rt::ImageFormat::ppm;
        f.samples = {x1 - x0, y1 - y0, 3, 8,
                     std::vector<std::uint8_t>(static_cast<std::size_t>((x1 - x0) * (y1 - y0) * 3))};
        f.metadata.set(std::string(rt::kRegionKey), std::to_string(x0) + "," + std::to_string(x1) + "," +
                                           std::to_string(y0) + "," + std::to_string(y1));
        f.metadata.set(std::string(rt::kFullSizeKey), "7x5");
        pieces.push_back({name, f});
    };
    piece("a", 0, 0, 7, 2);  // rows 0-1
    piece("b", 0, 2, 3, 5);  // columns 0-2 of rows 2-4
    piece("c", 4, 2, 6, 4);  // columns 4-5 of rows 2-3: column 3, column 6 and (4-5, 4) left
    std::string message;
    try {
        rt::merge_pieces(pieces);
    } catch (const rt::Error& e) {
        message = e.what();
    }
    CHECK_EQ(message, std::string("the pieces leave a gap: 8 pixels within columns 3-6, rows "
                                  "2-4 of the 7x5 image are in no piece"));
    piece("d", 3, 2, 4, 5);
    piece("e", 6, 2, 7, 5);
    piece("f", 4, 4, 6, 5);
    CHECK_EQ(rt::merge_pieces(pieces).width(), 7);
}

TEST(info_names_the_file_and_describes_an_image_with_half_a_region) {
    // Finding 12: "rtimg: records only one of Region and Full-Size", no file, nothing described.
    const fs::path dir = rt_test::work_dir("image-hostile-info");
    write_file(dir / "half.ppm", "P6\n# Region: 0,1,0,1\n1 1\n255\n\x01\x02\x03"s);
    const rt_test::RunResult r = run_rtimg(dir, "info half.ppm");
    CHECK_EQ(r.status, 0);
    CHECK_CONTAINS(r.out, "size: 1x1\n");
    CHECK_CONTAINS(r.out, "region: unreadable (records only one of Region and Full-Size)\n");
    CHECK_CONTAINS(r.out, "red  1  1  1\n");
    CHECK_EQ(r.err, std::string("rtimg: warning: half.ppm records only one of Region and "
                                "Full-Size\n"));
}
