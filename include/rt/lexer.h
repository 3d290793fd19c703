// Splits a scene into whitespace-separated tokens, dropping # comments, and remembers where
// each token starts.
#pragma once

#include <cstddef>
#include <istream>
#include <optional>
#include <string>
#include <string_view>

namespace rt {

struct Location {
    int line = 1;
    int column = 1;
};

struct Token {
    std::string text;
    Location where;
    bool quoted = false;  // a "double-quoted" path, which may be empty
    bool end = false;     // no more tokens: `where` is the end of the input

    bool at_end() const { return end; }
};

// The longest token rt accepts; a longer one is an error, so no input makes the lexer
// allocate without bound.
inline constexpr std::size_t kMaxTokenLength = 4096;

class Lexer {
  public:
    Lexer(std::istream& in, std::string name) : in_(in), name_(std::move(name)) {}

    // The next token without consuming it.
    const Token& peek();
    Token next();

    const std::string& name() const { return name_; }
    // Throws rt::Error with the message prefixed by "name:line:col: ".
    [[noreturn]] void fail(Location where, std::string_view message) const;

  private:
    int get();
    Token scan();

    std::istream& in_;
    std::string name_;
    std::optional<Token> peeked_;
    Location here_;
};

}  // namespace rt
