// Splits a scene into whitespace-separated tokens, dropping # comments, and remembers where
// each token starts.
#pragma once

#include <cstddef>
#include <cstdint>
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

    const std::string& name() const { return names_.front(); }
    // "name:line:col", where `name` is the input's or the one a line marker gave.
    std::string place(Location where) const;
    // Throws rt::Error with the message prefixed by "name:line:col: ".
    [[noreturn]] void fail(Location where, std::string_view message) const;

  private:
    // The input is read in chunks of this many bytes, not a character at a time.
    static constexpr std::size_t kChunkSize = 64 * 1024;
    // Bytes allocated after the chunk, so that the token scan may read whole words there.
    static constexpr std::size_t kChunkSlack = 8;

    bool fill();
    void scan();
    bool scan_fast();
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
    std::string copy_;           // the text of a quoted token, or of one that crosses a chunk's end
    bool peeked_ = false;        // token_ holds the next token, not yet consumed
    Location here_;              // where chunk_[pos_] is in the input
    Location after_last_;        // just after the last token's last byte
    bool line_is_blank_ = true;  // nothing but blanks so far on this line: a marker may start
    std::string comment_;        // a comment that may be a line marker, as read so far
    bool marker_pending_ = false;  // the comment just read was a marker: the next line is ...
    Location marker_;              // ... this line of this file
};

}  // namespace rt
