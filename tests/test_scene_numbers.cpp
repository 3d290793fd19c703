// The reader's fast number path and the lexer's places: every number it reads has the bits
// from_chars (and strtod) give for the same text, and every token the place a plain count of
// lines and bytes gives, whatever the chunk boundaries, blanks and comments around it.
#include <bit>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "check.h"
#include "common/message_text.h"
#include "rt/reader.h"
#include "scene/lexer.h"

using namespace rt;
using namespace rt_test;

namespace {

// The value the reader gave before its fast path: from_chars where it reads the whole token,
// else strtod.
double reference_value(const std::string& text) {
    double value = 0;
    const auto [stop, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error == std::errc{} && stop == text.data() + text.size()) return value;
    return std::strtod(text.c_str(), nullptr);
}

// Numbers of every spelling the fast path takes and some it leaves: signs, leading zeros,
// long fractions, exponents, more digits than 2^53 or 19 hold, zeros of both signs.
std::string random_number(std::mt19937_64& random) {
    const auto pick = [&](int n) { return static_cast<int>(random() % static_cast<unsigned>(n)); };
    std::string text;
    if (pick(3) == 0) text += '-';
    if (pick(8) == 0) text += std::string(static_cast<std::size_t>(pick(4)), '0');
    const int whole_digits = 1 + pick(pick(4) == 0 ? 20 : 6);
    for (int i = 0; i < whole_digits; ++i)
        text += static_cast<char>('0' + (i == 0 && pick(4) == 0 ? 0 : pick(10)));
    if (pick(3) != 0) {
        text += '.';
        const int fraction_digits = 1 + pick(pick(4) == 0 ? 24 : 9);
        for (int i = 0; i < fraction_digits; ++i) text += static_cast<char>('0' + pick(10));
    }
    if (pick(5) == 0) {
        text += pick(2) == 0 ? 'e' : 'E';
        const int sign = pick(3);
        if (sign == 1) text += '-';
        if (sign == 2) text += '+';
        text += std::to_string(pick(pick(3) == 0 ? 400 : 30));
    }
    return text;
}

std::string random_gap(std::mt19937_64& random) {
    static const char* const kGaps[] = {
        " ", " ", "\n", "  ", "\t", "\r\n", " \v ", "\f", " # a comment 1.5\n", "\n# x\n"};
    return kGaps[random() % (sizeof kGaps / sizeof kGaps[0])];
}

// Where each token of `text` starts, counted byte by byte: a line's first byte is column 1.
std::vector<Location> reference_places(const std::string& text) {
    std::vector<Location> places;
    Location here;
    bool in_token = false, in_comment = false;
    for (const char c : text) {
        const bool space =
            c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
        if (c == '\n') in_comment = false;
        if (!in_comment && c == '#') in_comment = true;
        const bool token_byte = !space && !in_comment;
        if (token_byte && !in_token) places.push_back(here);
        in_token = token_byte;
        if (c == '\n') {
            ++here.line;
            here.column = 1;
        } else {
            ++here.column;
        }
    }
    return places;
}

}  // namespace

TEST(numbers_have_the_bits_from_chars_gives) {
    std::mt19937_64 random(18);
    // Enough text to cross the lexer's 64 KiB chunks many times, so tokens straddle them.
    std::vector<std::string> numbers;
    std::string text;
    while (text.size() < 600'000) {
        numbers.push_back(random_number(random));
        text += numbers.back();
        text += random_gap(random);
    }
    const std::vector<Location> places = reference_places(text);
    CHECK_EQ(places.size(), numbers.size());
    // Each number read after a look at its place (the lexer's token), then without one (the
    // lexer hands a plain decimal straight to the reader), alternating in runs.
    std::istringstream in(text);
    SceneReader reader(in, "numbers.in", {});
    long tried = 0, fast = 0;
    for (std::size_t i = 0; i < numbers.size(); ++i) {
        const bool look = i / 7 % 2 == 0;
        const Location where = look ? reader.next_location() : places[i];
        const double expected = reference_value(numbers[i]);
        double value = 0;
        bool was_plain = false;
        if (std::isfinite(expected)) {
            // plain_number first, as meshes ask, or number() alone.
            if (i % 3 != 2) {
                was_plain = reader.plain_number(value);
                ++tried;
            }
            if (!was_plain) value = reader.number("number");
            if (std::bit_cast<std::uint64_t>(value) != std::bit_cast<std::uint64_t>(expected))
                CHECK_EQ(join(numbers[i], " read as ", value), join(numbers[i], " is ", expected));
        } else {
            // Out of range: refused with its place, as before.
            CHECK_ERROR(reader.number("number"),
                        join("numbers.in:", where.line, ':', where.column,
                             ": number must be a finite number, got ", quote_token(numbers[i])));
        }
        if (where.line != places[i].line || where.column != places[i].column)
            CHECK_EQ(join(where.line, ':', where.column),
                     join(places[i].line, ':', places[i].column));
        CHECK_EQ(reader.last_number_location().line, places[i].line);
        CHECK_EQ(reader.last_number_location().column, places[i].column);
        CHECK_EQ(reader.last_number_text(), show_token(numbers[i]));
        fast += was_plain ? 1 : 0;
    }
    // Most numbers take the fast path, and some do not.
    CHECK(fast > tried / 2);
    CHECK(fast < tried);
}

TEST(numbers_at_the_edges_of_the_fast_path) {
    // 2^53 and the numbers next to it, 19 and 20 digits, exponents of 22 and 23 each way,
    // negative zero, and forms the fast path leaves to from_chars and strtod.
    const std::vector<std::string> texts = {"9007199254740992",
                                            "9007199254740993",
                                            "9007199254740991",
                                            "1234567890123456789",
                                            "12345678901234567890",
                                            "0.1234567890123456789",
                                            "1e22",
                                            "1e23",
                                            "1e-22",
                                            "1e-23",
                                            "123456789e-22",
                                            "4.35e22",
                                            "-0",
                                            "-0.0",
                                            "0e400",
                                            "+1",
                                            ".5",
                                            "1.",
                                            "0x10",
                                            "000000000000000000001",
                                            "1.000000000000000000000001",
                                            "2.2250738585072014e-308",
                                            "1.7976931348623157e308",
                                            "5e-324",
                                            "0.30000000000000004",
                                            "9.999999999999999e22",
                                            "-1.5E+3"};
    std::string text;
    for (const std::string& t : texts) text += t + "\n";
    std::istringstream in(text);
    SceneReader reader(in, "edges.in", {});
    for (const std::string& t : texts) {
        const double value = reader.number("number");
        const double expected = reference_value(t);
        CHECK_EQ(std::bit_cast<std::uint64_t>(value), std::bit_cast<std::uint64_t>(expected));
        CHECK_EQ(std::signbit(value), std::signbit(expected));
    }
}

TEST(tokens_keep_their_places_across_chunks) {
    // Long tokens and comments placed so that some cross the 64 KiB chunk boundary, and line
    // markers, which the fast path leaves to the general one.
    std::mt19937_64 random(7);
    std::string text;
    while (text.size() < 300'000) {
        const int kind = static_cast<int>(random() % 5);
        if (kind == 0) text += std::string(1 + random() % 3000, 'x');
        if (kind == 1) text += "# " + std::string(random() % 5000, 'c');
        if (kind == 2) text += "\"a/path\"";
        if (kind >= 3) text += random_number(random);
        text += random_gap(random);
    }
    std::istringstream in(text);
    Lexer lexer(in, "places.in");
    std::vector<Location> seen;
    for (;;) {
        const Token& token = lexer.next();
        if (token.at_end()) break;
        seen.push_back(token.where);
    }
    const std::vector<Location> places = reference_places(text);
    CHECK_EQ(seen.size(), places.size());
    for (std::size_t i = 0; i < seen.size() && i < places.size(); ++i)
        if (seen[i].line != places[i].line || seen[i].column != places[i].column)
            CHECK_EQ(join(i, ": ", seen[i].line, ':', seen[i].column),
                     join(i, ": ", places[i].line, ':', places[i].column));
}

TEST(numbers_at_the_ends_of_chunks) {
    // The same kind of text shifted by 0 to 23 bytes, so that numbers end just before, at and
    // after the lexer's 64 KiB chunk ends, read with and without a look at their place first;
    // and a short last chunk, after whose end the buffer still holds the digits of the chunk
    // before (they must not join the last number).
    constexpr std::size_t kChunk = 64 * 1024;
    for (std::size_t shift = 0; shift < 24; ++shift) {
        for (const bool look : {false, true}) {
            std::string text(shift, ' ');
            std::vector<std::string> numbers;
            std::mt19937_64 random(shift);
            while (text.size() < 2 * kChunk + 40) {
                numbers.push_back(random_number(random));
                text += numbers.back();
                text += shift % 3 == 0 ? "\n" : " ";
            }
            // The last chunk: a few bytes, a number without a newline after it.
            numbers.push_back(shift % 2 == 0 ? "-7" : "0.25");
            text += numbers.back();
            std::istringstream in(text);
            SceneReader reader(in, "ends.in", {});
            const std::vector<Location> places = reference_places(text);
            CHECK_EQ(places.size(), numbers.size());
            for (std::size_t i = 0; i < numbers.size() && i < places.size(); ++i) {
                const double expected = reference_value(numbers[i]);
                if (!std::isfinite(expected)) {
                    CHECK_ERROR(
                        reader.number("number"),
                        join("ends.in:", places[i].line, ':', places[i].column,
                             ": number must be a finite number, got ", quote_token(numbers[i])));
                    continue;
                }
                if (look) {
                    const Location where = reader.next_location();
                    CHECK_EQ(join(where.line, ':', where.column),
                             join(places[i].line, ':', places[i].column));
                }
                const double value = reader.number("number");
                if (std::bit_cast<std::uint64_t>(value) != std::bit_cast<std::uint64_t>(expected))
                    CHECK_EQ(join(numbers[i], " read as ", value),
                             join(numbers[i], " is ", expected));
                const Location at = reader.last_number_location();
                if (at.line != places[i].line || at.column != places[i].column)
                    CHECK_EQ(join(i, ": ", at.line, ':', at.column),
                             join(i, ": ", places[i].line, ':', places[i].column));
                CHECK_EQ(reader.last_number_text(), show_token(numbers[i]));
            }
            CHECK_ERROR(
                reader.number("number"),
                join("ends.in:", places.back().line, ':',
                     places.back().column + static_cast<std::int64_t>(numbers.back().size()),
                     ": unexpected end of file: expected number"));
        }
    }
}
