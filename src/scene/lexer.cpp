// The lexer reads its input a chunk at a time through the stream buffer's sgetn (for a file,
// straight from the operating system) and scans each chunk with plain loops. A token that lies
// within one chunk is handed out as a view of the chunk's bytes; one that crosses a chunk's end,
// or a quoted path, is copied into one reused string, so reading allocates nothing once that
// has grown. The common case (blanks, then a plain token, often a decimal number whose value is
// computed on the way) takes one pass on local variables (scan_fast); everything else the
// general path. Places are counted in bytes, as before: a line's first byte is column 1.
#include "scene/lexer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <limits>

#include "common/ascii.h"
#include "rt/error.h"

namespace rt {

namespace {
bool ends_plain_token(char c) { return is_ascii_space(c) || c == '#'; }
// Whitespace that does not end the line.
bool is_blank(char c) { return is_ascii_space(c) && c != '\n'; }

// A comment longer than this is not a line marker, so a marker costs bounded memory.
constexpr std::size_t kMaxMarkerLength = kMaxTokenLength + 32;

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
constexpr std::array<Byte, 256> kByteClasses = make_byte_classes();

Byte byte_class(char c) { return kByteClasses[static_cast<unsigned char>(c)]; }

// Powers of ten that a double holds exactly.
constexpr std::array<double, 23> kExactPowersOfTen = {
    1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

// A run of decimal digits from p, added to `whole` (which wraps when there are more than 19:
// callers count them); returns its end.
const char* take_digits(const char* p, const char* end, std::uint64_t& whole) {
    for (; p < end; ++p) {
        const auto digit = static_cast<unsigned>(static_cast<unsigned char>(*p)) - '0';
        if (digit > 9) break;
        whole = whole * 10 + digit;
    }
    return p;
}

// The value of (-1)^negative whole 10^exponent when it can be had exactly the way from_chars
// and strtod round it: whole (at most 19 digits) at most 2^53 and the exponent within
// [-22, 22]. Then whole and 10^|exponent| are exact doubles, so the one rounded multiplication
// or division gives the correctly rounded value. False otherwise.
bool exact_decimal(std::uint64_t whole, int exponent, bool negative, double& value) {
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

// A plain decimal (Token::decimal): an optional '-', digits, optionally a point and more
// digits, optionally an exponent ('e' or 'E', an optional sign, at most four digits), at most
// 19 digits before the exponent (leading zeros counted), whose value exact_decimal gives.
bool parse_plain_decimal(std::string_view text, double& value) {
    const char* p = text.data();
    const char* const end = p + text.size();
    const bool negative = p < end && *p == '-';
    if (negative) ++p;
    std::uint64_t whole = 0;
    const char* const first = p;
    p = take_digits(p, end, whole);
    if (p == first) return false;
    std::ptrdiff_t digits = p - first;
    int exponent = 0;
    if (p < end && *p == '.') {
        const char* const fraction = ++p;
        p = take_digits(p, end, whole);
        if (p == fraction || p - fraction > 19) return false;
        digits += p - fraction;
        exponent = -static_cast<int>(p - fraction);
    }
    if (digits > 19) return false;
    if (p < end) {
        if (*p != 'e' && *p != 'E') return false;
        ++p;
        const bool below = p < end && *p == '-';
        if (p < end && (*p == '-' || *p == '+')) ++p;
        std::uint64_t written = 0;
        const char* const exponent_digits = p;
        p = take_digits(p, end, written);
        if (p == exponent_digits || p - exponent_digits > 4 || p != end) return false;
        exponent += below ? -static_cast<int>(written) : static_cast<int>(written);
    }
    return exact_decimal(whole, exponent, negative, value);
}

// Eight bytes at a time, the bytes that end a plain token or are never in one: whitespace,
// '#', a control byte (all at most 0x20, or '#', or 0x7f). Returns a mask whose lowest set bit,
// if any, is the high bit of the first such byte in memory order (little-endian loads); bits
// above it may be set by the borrows of the subtractions, which is why only the lowest counts.
// A byte from 0x80 on is plain (the `& ~word`).
std::uint64_t token_ends(std::uint64_t word) {
    constexpr std::uint64_t kOnes = 0x0101010101010101;
    constexpr std::uint64_t kHigh = 0x8080808080808080;
    const auto zero_bytes = [](std::uint64_t x) { return (x - kOnes) & ~x & kHigh; };
    const std::uint64_t below_0x21 = (word - kOnes * 0x21) & ~word & kHigh;
    return below_0x21 | zero_bytes(word ^ (kOnes * '#')) | zero_bytes(word ^ (kOnes * 0x7f));
}

// Reads `#line N "path"` (blanks between, nothing but blanks after): N >= 1 and a non-empty
// path without quotes. Anything else is an ordinary comment.
bool parse_line_marker(std::string_view text, int& line, std::string_view& path) {
    constexpr std::string_view kKeyword = "#line";
    if (text.substr(0, kKeyword.size()) != kKeyword) return false;
    std::size_t i = kKeyword.size();
    const auto skip_blanks = [&] {
        const std::size_t start = i;
        while (i < text.size() && is_blank(text[i])) ++i;
        return i > start;
    };
    if (!skip_blanks()) return false;
    long value = 0;
    const std::size_t digits_start = i;
    while (i < text.size() && text[i] >= '0' && text[i] <= '9') {
        value = value * 10 + (text[i] - '0');
        if (value > std::numeric_limits<int>::max()) return false;
        ++i;
    }
    if (i == digits_start || value < 1 || !skip_blanks()) return false;
    if (i >= text.size() || text[i] != '"') return false;
    const std::size_t close = text.find('"', i + 1);
    if (close == std::string_view::npos || close == i + 1) return false;
    path = text.substr(i + 1, close - i - 1);
    // Messages print the path: a control byte in it would reach the terminal.
    for (const char c : path)
        if (is_control(static_cast<unsigned char>(c))) return false;
    i = close + 1;
    skip_blanks();
    if (i != text.size()) return false;
    line = static_cast<int>(value);
    return true;
}
}  // namespace

Lexer::Lexer(std::istream& in, std::string name)
    : in_(in), names_{std::move(name)}, chunk_(new char[kChunkSize + kChunkSlack]()) {}

std::string Lexer::place(Location where) const {
    return names_[static_cast<std::size_t>(where.file)] + ":" + std::to_string(where.line) + ":" +
           std::to_string(where.column);
}

void Lexer::fail(Location where, std::string_view message) const {
    throw Error(place(where) + ": " + std::string(message));
}

// A newline: the next line is the following one, or the one a marker just named.
void Lexer::end_line() {
    ++pos_;
    if (marker_pending_) {
        here_ = marker_;
        marker_pending_ = false;
    } else {
        ++here_.line;
    }
    here_.column = 1;
    line_is_blank_ = true;
}

void Lexer::note_line_marker() {
    int line = 0;
    std::string_view path;
    if (!parse_line_marker(comment_, line, path)) return;
    marker_.line = line;
    marker_.column = 1;
    // The same name as the last marker's (the usual case) reuses its index.
    if (names_.back() == path && names_.size() > 1) {
        marker_.file = static_cast<int>(names_.size() - 1);
    } else if (names_.front() == path) {
        marker_.file = 0;
    } else {
        names_.emplace_back(path);
        marker_.file = static_cast<int>(names_.size() - 1);
    }
    marker_pending_ = true;
}

// Reads the next chunk when the current one is used up; false at the end of the input.
bool Lexer::fill() {
    if (pos_ < end_) return true;
    std::streambuf* buf = in_.rdbuf();
    const std::streamsize got =
        buf ? buf->sgetn(chunk_.get(), static_cast<std::streamsize>(kChunkSize)) : 0;
    pos_ = 0;
    end_ = got > 0 ? static_cast<std::size_t>(got) : 0;
    return end_ > 0;
}

void Lexer::skip_space_and_comments() {
    while (fill()) {
        const Byte kind = byte_class(chunk_[pos_]);
        if (kind == Byte::newline) {
            end_line();
        } else if (kind == Byte::blank) {
            // A run of blanks at once: the column moves by its length.
            const char* const start = chunk_.get() + pos_;
            const char* const limit = chunk_.get() + end_;
            const char* stop = start + 1;
            while (stop < limit && byte_class(*stop) == Byte::blank) ++stop;
            const auto length = static_cast<std::size_t>(stop - start);
            pos_ += length;
            here_.column += static_cast<std::int64_t>(length);
        } else if (kind == Byte::hash) {
            // To the end of the line, leaving the newline for the case above. A comment that
            // starts its line may be a line marker, so its text is kept (up to a bound).
            bool may_be_marker = line_is_blank_;
            comment_.clear();
            for (;;) {
                const char* start = chunk_.get() + pos_;
                const auto* newline =
                    static_cast<const char*>(std::memchr(start, '\n', end_ - pos_));
                const std::size_t skipped =
                    newline ? static_cast<std::size_t>(newline - start) : end_ - pos_;
                if (may_be_marker) {
                    if (comment_.size() + skipped > kMaxMarkerLength)
                        may_be_marker = false;
                    else
                        comment_.append(start, skipped);
                }
                pos_ += skipped;
                here_.column += static_cast<std::int64_t>(skipped);
                if (newline || !fill()) break;
            }
            line_is_blank_ = false;
            if (may_be_marker) note_line_marker();
        } else {
            return;
        }
    }
}

void Lexer::scan() {
    token_.quoted = false;
    token_.decimal = false;
    if (scan_fast()) return;
    skip_space_and_comments();
    token_.where = here_;
    token_.end = !fill();
    if (token_.end) {
        token_.text = {};
        token_.where = after_last_;
        return;
    }
    line_is_blank_ = false;
    if (chunk_[pos_] == '"') {
        scan_quoted();
        check_controls();
    } else {
        scan_plain();
        check_controls();
        token_.decimal = parse_plain_decimal(token_.text, token_.value);
    }
    after_last_ = here_;
}

// A NUL or an escape in a token is never part of a number or a path rt can use; taking the
// token up to it would accept input that is not what it looks like.
void Lexer::check_controls() const {
    const std::string_view text = token_.text;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (!is_control(static_cast<unsigned char>(text[i]))) continue;
        Location at = token_.where;
        at.column += static_cast<std::int64_t>(i) + (token_.quoted ? 1 : 0);
        fail(at, "control character " + show_token(text.substr(i, 1)) + " in token " +
                     quote_token(text));
    }
}

void Lexer::scan_quoted() {
    token_.quoted = true;
    copy_.clear();
    ++pos_;
    ++here_.column;
    for (;;) {
        if (!fill() || chunk_[pos_] == '\n') fail(token_.where, "unterminated quoted path");
        const char c = chunk_[pos_++];
        ++here_.column;
        if (c == '"') break;
        if (copy_.size() >= kMaxTokenLength)
            fail(token_.where,
                 "quoted path longer than " + std::to_string(kMaxTokenLength) + " characters");
        copy_.push_back(c);
    }
    token_.text = copy_;
}

// The common case in one pass, on local copies of the place: blanks and newlines, then a plain
// token of printable bytes that ends before the chunk does and is not too long, whose text is
// then the chunk's own bytes. Anything else (a comment, a line marker to apply, a quoted
// path, a control byte, the chunk's end) returns false having changed nothing, and scan()
// takes the general path from the same byte.
bool Lexer::scan_fast() {
    const char* const base = chunk_.get();
    const char* const limit = base + end_;
    const char* p = base + pos_;
    std::int64_t line = here_.line;
    std::int64_t column = here_.column;
    for (;; ++p) {
        if (p == limit) return false;
        const Byte kind = byte_class(*p);
        if (kind == Byte::plain) break;
        if (kind == Byte::blank) {
            ++column;
        } else if (kind == Byte::newline && !marker_pending_) {
            ++line;
            column = 1;
        } else {
            return false;
        }
    }
    if (*p == '"') return false;
    const char* const start = p;
    // The digits of a decimal are read as the token is scanned: [-]digits[.digits] ends here
    // when a blank, a newline or a comment follows. Anything else goes on as a token from the
    // first byte that is not part of such a decimal (one with an exponent is read below).
    bool decimal = false;
    double value = 0;
    {
        const bool negative = *p == '-';
        const char* const digits = p + (negative ? 1 : 0);
        std::uint64_t whole = 0;
        const char* q = take_digits(digits, limit, whole);
        std::ptrdiff_t count = q - digits;
        int exponent = 0;
        if (count > 0 && q < limit && *q == '.') {
            const char* const fraction = q + 1;
            q = take_digits(fraction, limit, whole);
            exponent = -static_cast<int>(q - fraction);
            count = q == fraction ? 0 : count + (q - fraction);
        }
        if (q < limit) {
            const Byte after = byte_class(*q);
            if (after == Byte::blank || after == Byte::newline || after == Byte::hash)
                decimal =
                    count > 0 && count <= 19 && exact_decimal(whole, exponent, negative, value);
        }
        p = q;
    }
    const char* const stop_limit =
        start + std::min(static_cast<std::size_t>(limit - start), kMaxTokenLength + 1);
    if (p >= stop_limit) return false;  // the chunk ends, or the token is too long
    if (decimal) {
        // Its end is found already.
    } else if constexpr (std::endian::native == std::endian::little) {
        // The chunk has kChunkSlack bytes after its end, so a word may be read there; the
        // bytes past `limit` only ever count as the chunk's end.
        for (;;) {
            std::uint64_t word = 0;
            std::memcpy(&word, p, sizeof word);
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
    if (p == stop_limit || byte_class(*p) == Byte::control) return false;
    const auto length = static_cast<std::size_t>(p - start);
    token_.where = {line, column, here_.file};
    token_.text = std::string_view(start, length);
    token_.end = false;
    // A number with an exponent is read the general way, once.
    if (!decimal) decimal = parse_plain_decimal(token_.text, value);
    token_.decimal = decimal;
    token_.value = value;
    here_.line = line;
    here_.column = column + static_cast<std::int64_t>(length);
    pos_ = static_cast<std::size_t>(p - base);
    line_is_blank_ = false;
    after_last_ = here_;
    return true;
}

// A run of characters up to whitespace, '#' or the end of the input, copied a chunk's worth
// at a time.
void Lexer::scan_plain() {
    copy_.clear();
    do {
        const char* start = chunk_.get() + pos_;
        const char* limit = chunk_.get() + end_;
        const char* stop = std::find_if(start, limit, ends_plain_token);
        const auto length = static_cast<std::size_t>(stop - start);
        if (copy_.size() + length > kMaxTokenLength)
            fail(token_.where,
                 "token longer than " + std::to_string(kMaxTokenLength) + " characters");
        copy_.append(start, length);
        pos_ += length;
        here_.column += static_cast<std::int64_t>(length);
    } while (pos_ == end_ && fill());
    token_.text = copy_;
}

}  // namespace rt
