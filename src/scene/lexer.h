// Splits a scene into whitespace-separated tokens, dropping # comments, and remembers where
// each token starts.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <istream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "common/message_text.h"  // how messages show a token
#include "rt/error.h"
#include "rt/limits.h"

namespace rt {

struct Token {
    // The token's bytes (without a quoted path's quotes), valid until the next call to peek or
    // next: they are the input's own bytes where the token lies within one chunk, else a copy.
    std::string_view text;
    Location where;
    bool quoted = false;  // a "double-quoted" path, which may be empty
    // A plain decimal: an optional '-', digits, a point and digits, an exponent, whose value
    // the lexer computed exactly as from_chars and strtod round it (see lexer.cpp): value.
    // Other numbers are left to the reader.
    bool decimal = false;
    double value = 0;
    bool end = false;  // no more tokens: `where` is just after the last token, where the
                       // reader stopped (as compilers report it), or 1:1 for no tokens

    bool at_end() const { return end; }
};

// The longest plain decimal (Token::decimal): '-', 19 digits, a point, 'e', a sign and four
// digits.
inline constexpr std::size_t kMaxDecimalLength = 27;
// A plain decimal's text may be read this many bytes from its start (the bytes after the
// token are the input's or padding), so that a reader copies it with one fixed-size copy.
inline constexpr std::size_t kDecimalReadable = 32;
static_assert(kDecimalReadable >= kMaxDecimalLength);

class Lexer {
  public:
    Lexer(std::istream& in, std::string name);

    // The next token without consuming it.
    const Token& peek() {
        if (!peeked_) {
            scan();
            peeked_ = true;
        }
        return token_;
    }
    // The next token, consumed. The reference stays valid until the next call to peek or next
    // (the lexer reuses one token, so reading allocates nothing once its copy has grown).
    const Token& next() {
        peek();
        peeked_ = false;
        return token_;
    }

    // The next token when it is a plain decimal (Token::decimal), consumed: its value, its
    // place, and its text, copied as kDecimalReadable bytes to `text` (of which `size` are the
    // token's). Otherwise false, with the token peeked and nothing else changed.
    inline bool next_decimal(double& value, Location& where, char* text, unsigned char& size);

    const std::string& name() const { return names_.front(); }
    // "name:line:col", where `name` is the input's or the one a line marker gave.
    std::string place(Location where) const;
    // Throws rt::Error with the message prefixed by "name:line:col: ".
    [[noreturn]] void fail(Location where, std::string_view message) const;

  private:
    // The input is read in chunks of this many bytes, not a character at a time.
    static constexpr std::size_t kChunkSize = 64 * 1024;
    // Bytes allocated after the chunk, so that the token scan may read whole words there and
    // a decimal's kDecimalReadable bytes lie within it; the first is a NUL (fill).
    static constexpr std::size_t kChunkSlack = kDecimalReadable;

    bool fill();
    // Where scan_fast puts a decimal that next_decimal takes.
    struct DecimalSink {
        double* value;
        Location* where;
        char* text;
        unsigned char* size;
    };
    enum class Fast {
        none,   // not the common case: nothing changed, scan_general takes it
        token,  // token_ holds the token
        taken,  // a decimal, written to the sink and consumed
    };
    void scan();
    inline Fast scan_fast(const DecimalSink* sink);
    [[gnu::noinline]] void scan_general();
    void skip_space_and_comments();
    void scan_quoted();
    void scan_plain();
    void check_controls() const;
    void end_line();
    void note_line_marker();

    std::istream& in_;
    std::vector<std::string> names_;  // the input's name, then each name a marker gave
    std::unique_ptr<char[]> chunk_;
    std::size_t pos_ = 0;  // the next unread byte of chunk_
    std::size_t end_ = 0;  // one past the last byte read into chunk_
    Token token_;
    std::string copy_;  // the text of a quoted token, or of one that crosses a chunk's end
    // A decimal's text from copy_, where kDecimalReadable bytes may be read.
    char decimal_copy_[kDecimalReadable] = {};
    bool peeked_ = false;          // token_ holds the next token, not yet consumed
    Location here_;                // where chunk_[pos_] is in the input
    Location after_last_;          // just after the last token's last byte
    bool line_is_blank_ = true;    // nothing but blanks so far on this line: a marker may start
    std::string comment_;          // a comment that may be a line marker, as read so far
    bool marker_pending_ = false;  // the comment just read was a marker: the next line is ...
    Location marker_;              // ... this line of this file
};

// The lexer's common case (Lexer::scan_fast, Lexer::next_decimal) is defined here, inline, so
// that a reader's number() compiles into one function with it; the rest is in lexer.cpp.
namespace lexer_detail {

constexpr bool is_control(unsigned char c) { return c < 0x20 || c == 0x7f; }

// What a byte does in the scanning loops, looked up in one table instead of several tests.
enum class Byte : unsigned char {
    plain,    // part of a token (any byte from 0x80 on too)
    blank,    // whitespace that does not end the line
    newline,  // '\n'
    hash,     // '#': a comment starts
    control,  // a control byte that is not whitespace: never in a token
};

constexpr std::array<Byte, 256> make_byte_classes() {
    std::array<Byte, 256> classes{};
    for (int i = 0; i < 256; ++i) {
        const char c = static_cast<char>(i);
        // is_ascii_space's set, spelled out for a constant expression.
        const bool space =
            c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
        classes[static_cast<std::size_t>(i)] = c == '\n'  ? Byte::newline
                                               : space    ? Byte::blank
                                               : c == '#' ? Byte::hash
                                               : is_control(static_cast<unsigned char>(i))
                                                   ? Byte::control
                                                   : Byte::plain;
    }
    return classes;
}
inline constexpr std::array<Byte, 256> kByteClasses = make_byte_classes();

inline Byte byte_class(char c) { return kByteClasses[static_cast<unsigned char>(c)]; }

// Powers of ten that a double holds exactly.
inline constexpr std::array<double, 23> kExactPowersOfTen = {
    1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

// Eight bytes from p (in memory order on a little-endian machine: p[0] is the lowest byte).
inline std::uint64_t load_word(const char* p) {
    std::uint64_t word = 0;
    std::memcpy(&word, p, sizeof word);
    return word;
}

// A run of decimal digits from p, added to `whole` (which wraps when there are more than 19:
// callers count them); returns its end. The run must end before the readable bytes do (a
// chunk ends with a NUL, see Lexer::fill): there is no test of the end. A byte at a time: a word at
// a time (SWAR) was tried and was slower, as the next token's place then waits on the arithmetic,
// where a loop's predicted branches let the processor run ahead.
inline const char* take_run(const char* p, std::uint64_t& whole) {
    for (;; ++p) {
        const auto digit = static_cast<unsigned>(static_cast<unsigned char>(*p)) - '0';
        if (digit > 9) return p;
        whole = whole * 10 + digit;
    }
}

// The value of (-1)^negative whole 10^exponent when it can be had exactly the way from_chars
// and strtod round it: whole (at most 19 digits) at most 2^53 and the exponent within
// [-22, 22]. Then whole and 10^|exponent| are exact doubles, so the one rounded multiplication
// or division gives the correctly rounded value. False otherwise.
inline bool exact_decimal(std::uint64_t whole, int exponent, bool negative, double& value) {
    constexpr std::uint64_t kExactWhole = std::uint64_t{1} << 53;
    double magnitude = 0;
    if (whole != 0) {
        if (whole > kExactWhole || exponent < -22 || exponent > 22) return false;
        const double w = static_cast<double>(whole);
        magnitude = exponent < 0 ? w / kExactPowersOfTen[static_cast<std::size_t>(-exponent)]
                                 : w * kExactPowersOfTen[static_cast<std::size_t>(exponent)];
    }
    value = negative ? -magnitude : magnitude;
    return true;
}

// A plain decimal (Token::decimal), with an exponent or not (lexer.cpp).
bool parse_plain_decimal(std::string_view text, double& value);

// Eight bytes at a time, the bytes that end a plain token or are never in one: whitespace,
// '#', a control byte (all at most 0x20, or '#', or 0x7f). Returns a mask whose lowest set bit,
// if any, is the high bit of the first such byte in memory order (little-endian loads); bits
// above it may be set by the borrows of the subtractions, which is why only the lowest counts.
// A byte from 0x80 on is plain (the `& ~word`).
inline std::uint64_t token_ends(std::uint64_t word) {
    constexpr std::uint64_t kOnes = 0x0101010101010101;
    constexpr std::uint64_t kHigh = 0x8080808080808080;
    const auto zero_bytes = [](std::uint64_t x) { return (x - kOnes) & ~x & kHigh; };
    const std::uint64_t below_0x21 = (word - kOnes * 0x21) & ~word & kHigh;
    return below_0x21 | zero_bytes(word ^ (kOnes * '#')) | zero_bytes(word ^ (kOnes * 0x7f));
}

}  // namespace lexer_detail

// The common case in one pass, on local copies of the place: blanks and newlines, then a plain
// token of printable bytes that ends before the chunk does and is not too long, whose text is
// then the chunk's own bytes. Anything else (a comment, a line marker to apply, a quoted
// path, a control byte, the chunk's end) returns Fast::none having changed nothing, and
// scan_general takes it from the same byte. The chunk's end needs no test of its own: the
// byte there is a NUL (fill), a control byte, which ends every loop here as any other does.
// With a sink (next_decimal), a decimal is written there and consumed instead of becoming
// token_: its place and value go from registers, where reading back token_ just stored would
// wait for the stores (the processor forwards no load from two stores).
[[gnu::always_inline]] inline Lexer::Fast Lexer::scan_fast(const DecimalSink* sink) {
    using namespace lexer_detail;
    const char* const base = chunk_.get();
    const char* const limit = base + end_;
    const char* p = base + pos_;
    std::int64_t line = here_.line;
    std::int64_t column = here_.column;
    for (;; ++p) {
        const Byte kind = byte_class(*p);
        if (kind == Byte::plain) break;
        if (kind == Byte::blank) {
            ++column;
        } else if (kind == Byte::newline && !marker_pending_) {
            ++line;
            column = 1;
        } else {
            return Fast::none;  // a comment, a marker's line, a control byte, the chunk's end
        }
    }
    if (*p == '"') return Fast::none;
    const char* const start = p;
    // The digits of a decimal are read as the token is scanned: [-]digits[.digits] ends here
    // when a blank, a newline or a comment follows. Anything else goes on as a token from the
    // first byte that is not part of such a decimal (one with an exponent is read below).
    // No run of digits passes the chunk's end, where the byte is a NUL.
    bool decimal = false;
    double value = 0;
    {
        const bool negative = *p == '-';
        const char* const digits = p + (negative ? 1 : 0);
        std::uint64_t whole = 0;
        const char* q = take_run(digits, whole);
        std::ptrdiff_t count = q - digits;
        int exponent = 0;
        if (count > 0 && *q == '.') {
            const char* const fraction = q + 1;
            q = take_run(fraction, whole);
            exponent = -static_cast<int>(q - fraction);
            count = q == fraction ? 0 : count + (q - fraction);
        }
        // At limit, the NUL is no blank: a token that reaches the chunk's end is not read here.
        const Byte after = byte_class(*q);
        if (after != Byte::blank && after != Byte::newline && after != Byte::hash) {
            // Not a plain decimal without an exponent.
        } else if (count > 0 && count <= 15) {
            // exact_decimal's case without its tests: fewer than 2^53 and 10^15 are exact, and
            // the exponent is -(fraction digits), from -15 to 0, so the one division rounds
            // once; a whole number needs none (the division by 10^0 would be exact, and slow).
            // The sign is set without a branch (the magnitude is +0 or more, so this is its
            // negation, -0 for +0).
            double magnitude = static_cast<double>(whole);
            if (exponent != 0) magnitude /= kExactPowersOfTen[static_cast<std::size_t>(-exponent)];
            value = std::bit_cast<double>(std::bit_cast<std::uint64_t>(magnitude) |
                                          (std::uint64_t{negative} << 63));
            decimal = true;
        } else {
            decimal = count > 0 && count <= 19 && exact_decimal(whole, exponent, negative, value);
        }
        p = q;
    }
    if (!decimal) {
        // A decimal's end is found already: a blank, a newline or a '#', before the chunk's
        // end and within kMaxTokenLength (it has at most 21 bytes). Any other token goes on.
        const char* const stop_limit =
            start + std::min(static_cast<std::size_t>(limit - start), kMaxTokenLength + 1);
        if (p >= stop_limit) return Fast::none;  // the chunk ends, or the token is too long
        if constexpr (std::endian::native == std::endian::little) {
            // The chunk has kChunkSlack bytes after its end, so a word may be read there; the
            // bytes past `limit` only ever count as the chunk's end.
            for (;;) {
                const std::uint64_t word = load_word(p);
                if (const std::uint64_t ends = token_ends(word)) {
                    p += std::countr_zero(ends) / 8;
                    break;
                }
                p += sizeof word;
                if (p >= stop_limit) break;
            }
            if (p > stop_limit) p = stop_limit;
        } else {
            while (p < stop_limit && byte_class(*p) == Byte::plain) ++p;
        }
        if (p == stop_limit || byte_class(*p) == Byte::control) return Fast::none;
    }
    const auto length = static_cast<std::size_t>(p - start);
    const int file = here_.file;
    const std::int64_t after_column = column + static_cast<std::int64_t>(length);
    // A number with an exponent is read the general way, once.
    if (!decimal) decimal = parse_plain_decimal(std::string_view(start, length), value);
    Fast scanned = Fast::token;
    if (decimal && sink != nullptr) {
        *sink->value = value;
        *sink->where = {line, column, file};
        std::memcpy(sink->text, start, kDecimalReadable);  // the chunk's slack holds them
        *sink->size = static_cast<unsigned char>(length);
        scanned = Fast::taken;
    } else {
        token_.where = {line, column, file};
        token_.text = std::string_view(start, length);
        token_.end = false;
        token_.quoted = false;
        token_.decimal = decimal;
        token_.value = value;
    }
    // The place after the token, stored from registers: copying here_ to after_last_ would
    // read back the bytes just stored.
    here_.line = line;
    here_.column = after_column;
    after_last_ = {line, after_column, file};
    pos_ = static_cast<std::size_t>(p - base);
    line_is_blank_ = false;
    return scanned;
}

// Inline (and scan_fast with it) so that SceneReader::number is one function for the common
// case: a call less per number, and nothing stored only to be read back at once.
[[gnu::always_inline]] inline bool Lexer::next_decimal(double& value, Location& where, char* text,
                                                       unsigned char& size) {
    if (!peeked_) {
        // The common case: scan_fast hands the decimal over from its registers, consumed.
        const DecimalSink sink{&value, &where, text, &size};
        const Fast scanned = scan_fast(&sink);
        if (scanned == Fast::taken) return true;
        if (scanned == Fast::none) scan_general();
        peeked_ = true;
    }
    if (!token_.decimal) return false;
    peeked_ = false;
    value = token_.value;
    where = token_.where;
    std::memcpy(text, token_.text.data(), kDecimalReadable);
    size = static_cast<unsigned char>(token_.text.size());
    return true;
}

}  // namespace rt
