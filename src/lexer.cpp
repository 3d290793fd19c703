// The lexer reads its input a chunk at a time through the stream buffer's sgetn (for a file,
// straight from the operating system) and scans each chunk with plain loops. It keeps one
// token and reuses its string, so once that has grown, reading allocates nothing. Places are
// counted in bytes, as before: a line's first byte is column 1.
#include "rt/lexer.h"

#include <algorithm>
#include <cstring>

#include "rt/error.h"

namespace rt {

namespace {
bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}
bool ends_plain_token(char c) { return is_space(c) || c == '#'; }
}  // namespace

Lexer::Lexer(std::istream& in, std::string name)
    : in_(in), name_(std::move(name)), chunk_(new char[kChunkSize]) {}

void Lexer::fail(Location where, std::string_view message) const {
    throw Error(name_ + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) +
                ": " + std::string(message));
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
            ++pos_;
            ++here_.line;
            here_.column = 1;
        } else if (is_space(c)) {
            ++pos_;
            ++here_.column;
        } else if (c == '#') {
            // To the end of the line, leaving the newline for the case above.
            for (;;) {
                const char* start = chunk_.get() + pos_;
                const auto* newline =
                    static_cast<const char*>(std::memchr(start, '\n', end_ - pos_));
                const std::size_t skipped =
                    newline ? static_cast<std::size_t>(newline - start) : end_ - pos_;
                pos_ += skipped;
                here_.column += static_cast<int>(skipped);
                if (newline || !fill()) break;
            }
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
    if (token_.end) return;
    if (chunk_[pos_] == '"') {
        scan_quoted();
    } else {
        scan_plain();
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
        here_.column += static_cast<int>(length);
    } while (pos_ == end_ && fill());
}

}  // namespace rt
