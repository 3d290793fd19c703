// Splits readable source into tokens: numbers, names, "strings" and punctuation, each with its
// place. '#' comments run to the end of the line, as in the numeric format.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "rtpp/limits.h"
#include "rtpp/source.h"

namespace rtpp {

enum class TokenKind { number, name, string, punct, end };

struct Token {
    TokenKind kind = TokenKind::end;
    std::string text;  // the name, the string's contents, or the punctuation
    double number = 0;
    SourcePos pos;

    bool is(std::string_view punct) const { return kind == TokenKind::punct && text == punct; }
    bool is_name(std::string_view name) const { return kind == TokenKind::name && text == name; }
};

// The tokens of one file, ending with an end token. `file` is its index in SourceFiles.
std::vector<Token> tokenize(std::string_view text, int file, const Limits& limits);

// How a token is shown in messages: 'name', "string", end of file.
std::string describe(const Token& token);

}  // namespace rtpp
