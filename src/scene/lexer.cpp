// The lexer reads its input a chunk at a time through the stream buffer's sgetn (for a file,
// straight from the operating system) and scans each chunk with plain loops. It keeps one
// token and reuses its string, so once that has grown, reading allocates nothing. Places are
// counted in bytes, as before: a line's first byte is column 1.
#include "scene/lexer.h"

#include <algorithm>
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

bool is_control(unsigned char c) { return c < 0x20 || c == 0x7f; }

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
    : in_(in), names_{std::move(name)}, chunk_(new char[kChunkSize]) {}

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

const Token& Lexer::peek() {
    if (!peeked_) {
        scan();
        peeked_ = true;
    }
    return token_;
}

const Token& Lexer::next() {
    peek();
    peeked_ = false;
    return token_;
}

void Lexer::skip_space_and_comments() {
    while (fill()) {
        const char c = chunk_[pos_];
        if (c == '\n') {
            end_line();
        } else if (is_ascii_space(c)) {
            ++pos_;
            ++here_.column;
        } else if (c == '#') {
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
    token_.text.clear();
    token_.quoted = false;
    skip_space_and_comments();
    token_.where = here_;
    token_.end = !fill();
    if (token_.end) {
        token_.where = after_last_;
        return;
    }
    line_is_blank_ = false;
    if (chunk_[pos_] == '"') {
        scan_quoted();
    } else {
        scan_plain();
    }
    after_last_ = here_;
    // A NUL or an escape in a token is never part of a number or a path rt can use; taking the
    // token up to it would accept input that is not what it looks like.
    const std::string& text = token_.text;
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
    ++pos_;
    ++here_.column;
    for (;;) {
        if (!fill() || chunk_[pos_] == '\n') fail(token_.where, "unterminated quoted path");
        const char c = chunk_[pos_++];
        ++here_.column;
        if (c == '"') return;
        if (token_.text.size() >= kMaxTokenLength)
            fail(token_.where,
                 "quoted path longer than " + std::to_string(kMaxTokenLength) + " characters");
        token_.text.push_back(c);
    }
}

// A run of characters up to whitespace, '#' or the end of the input, copied a chunk's worth
// at a time.
void Lexer::scan_plain() {
    do {
        const char* start = chunk_.get() + pos_;
        const char* limit = chunk_.get() + end_;
        const char* stop = std::find_if(start, limit, ends_plain_token);
        const auto length = static_cast<std::size_t>(stop - start);
        if (token_.text.size() + length > kMaxTokenLength)
            fail(token_.where,
                 "token longer than " + std::to_string(kMaxTokenLength) + " characters");
        token_.text.append(start, length);
        pos_ += length;
        here_.column += static_cast<std::int64_t>(length);
    } while (pos_ == end_ && fill());
}

}  // namespace rt
