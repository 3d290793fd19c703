#include "rtpp/lexer.h"

#include <charconv>
#include <cmath>

namespace rtpp {

namespace {

bool is_name_start(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_name_char(char c) { return is_name_start(c) || is_digit(c); }

// Two-character operators first, so that "<=" is not read as "<" then "=".
constexpr std::string_view kTwoCharPuncts[] = {"<=", ">=", "==", "!="};
constexpr std::string_view kOneCharPuncts = "+-*/%^(){}<>,=.;";

}  // namespace

std::string describe(const Token& token) {
    switch (token.kind) {
        case TokenKind::end:
            return "end of file";
        case TokenKind::string:
            return "a string";
        default:
            return "'" + token.text + "'";
    }
}

std::vector<Token> tokenize(std::string_view text, int file, const Limits& limits) {
    std::vector<Token> tokens;
    std::size_t i = 0;
    int line = 1;
    std::size_t line_start = 0;
    const auto here = [&](std::size_t at) {
        return SourcePos{file, line, static_cast<int>(at - line_start + 1)};
    };
    while (true) {
        // Blanks, newlines and comments.
        while (i < text.size()) {
            const char c = text[i];
            if (c == '\n') {
                ++line;
                line_start = ++i;
            } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
                ++i;
            } else if (c == '#') {
                while (i < text.size() && text[i] != '\n') ++i;
            } else {
                break;
            }
        }
        Token token;
        token.pos = here(i);
        if (i >= text.size()) {
            tokens.push_back(std::move(token));
            return tokens;
        }
        const char c = text[i];
        if (is_digit(c) || (c == '.' && i + 1 < text.size() && is_digit(text[i + 1]))) {
            // Digits, a fraction and an exponent; no sign (minus is an operator) and no
            // hexadecimal, so "2e3" and "0.5" read as a person expects.
            std::size_t end = i;
            while (end < text.size() && is_digit(text[end])) ++end;
            if (end < text.size() && text[end] == '.') {
                ++end;
                while (end < text.size() && is_digit(text[end])) ++end;
            }
            if (end < text.size() && (text[end] == 'e' || text[end] == 'E')) {
                std::size_t exp = end + 1;
                if (exp < text.size() && (text[exp] == '+' || text[exp] == '-')) ++exp;
                if (exp < text.size() && is_digit(text[exp])) {
                    end = exp;
                    while (end < text.size() && is_digit(text[end])) ++end;
                }
            }
            if (end < text.size() && is_name_start(text[end]))
                fail(token.pos, "a number may not run into a name: '" +
                                    std::string(text.substr(i, end + 1 - i)) + "'");
            if (end - i > limits.string_length) fail(token.pos, "number too long");
            token.kind = TokenKind::number;
            token.text = text.substr(i, end - i);
            const auto [stop, error] =
                std::from_chars(text.data() + i, text.data() + end, token.number);
            if (error != std::errc{} || !std::isfinite(token.number))
                fail(token.pos, "number out of range: " + token.text);
            i = end;
        } else if (is_name_start(c)) {
            std::size_t end = i;
            while (end < text.size() && is_name_char(text[end])) ++end;
            if (end - i > limits.string_length)
                fail(token.pos,
                     "name longer than " + std::to_string(limits.string_length) + " characters");
            token.kind = TokenKind::name;
            token.text = text.substr(i, end - i);
            i = end;
        } else if (c == '"') {
            std::size_t end = i + 1;
            while (end < text.size() && text[end] != '"' && text[end] != '\n') ++end;
            if (end >= text.size() || text[end] != '"')
                fail(token.pos, "unterminated string (a string ends on its own line)");
            if (end - i - 1 > limits.string_length)
                fail(token.pos,
                     "string longer than " + std::to_string(limits.string_length) + " characters");
            token.kind = TokenKind::string;
            token.text = text.substr(i + 1, end - i - 1);
            i = end + 1;
        } else {
            token.kind = TokenKind::punct;
            for (std::string_view two : kTwoCharPuncts)
                if (text.substr(i, 2) == two) token.text = two;
            if (token.text.empty()) {
                if (kOneCharPuncts.find(c) == std::string_view::npos)
                    fail(token.pos, std::string("unexpected character '") + c + "'");
                token.text = std::string(1, c);
            }
            i += token.text.size();
        }
        tokens.push_back(std::move(token));
    }
}

}  // namespace rtpp
