// The lexer reads its input a chunk at a time through the stream buffer's sgetn (for a file,
// straight from the operating system) and scans each chunk with plain loops. A token that lies
// within one chunk is handed out as a view of the chunk's bytes; one that crosses a chunk's end,
// or a quoted path, is copied into one reused string, so reading allocates nothing once that
// has grown. The common case (blanks, then a plain token, often a decimal number whose value is
// computed on the way) takes one pass on local variables (scan_fast, inline in lexer.h, where
// next_decimal hands a reader its numbers); everything else the general path (scan_general).
// Places are counted in bytes, as before: a line's first byte is column 1.
#include "scene/lexer.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "common/ascii.h"
#include "rt/error.h"

namespace rt {

using namespace lexer_detail;

namespace {
bool ends_plain_token(char c) { return is_ascii_space(c) || c == '#'; }
// Whitespace that does not end the line.
bool is_blank(char c) { return is_ascii_space(c) && c != '\n'; }

// A comment longer than this is not a line marker, so a marker costs bounded memory.
constexpr std::size_t kMaxMarkerLength = kMaxTokenLength + 32;

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

}  // namespace

// A plain decimal (Token::decimal): an optional '-', digits, optionally a point and more
// digits, optionally an exponent ('e' or 'E', an optional sign, at most four digits), at most
// 19 digits before the exponent (leading zeros counted), whose value exact_decimal gives.
bool lexer_detail::parse_plain_decimal(std::string_view text, double& value) {
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

namespace {

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
    // A byte that ends every run the scans make (a control byte, not a digit), so that
    // scan_fast needs no test for the chunk's end: at `end_` it stops as at any control byte.
    chunk_[end_] = '\0';
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
    if (scan_fast(nullptr) == Fast::none) scan_general();
}

void Lexer::scan_general() {
    token_.quoted = false;
    token_.decimal = false;
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
        if (token_.decimal) {
            // Into a buffer that may be read kDecimalReadable bytes from its start, as the
            // chunk may (next_decimal copies that many).
            std::memcpy(decimal_copy_, token_.text.data(), token_.text.size());
            token_.text = std::string_view(decimal_copy_, token_.text.size());
        }
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
