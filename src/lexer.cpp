#include "rt/lexer.h"

#include <cctype>

#include "rt/error.h"

namespace rt {

namespace {
bool is_space(int c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}
}  // namespace

void Lexer::fail(Location where, std::string_view message) const {
    throw Error(name_ + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) +
                ": " + std::string(message));
}

int Lexer::get() {
    const int c = in_.rdbuf() ? in_.rdbuf()->sbumpc() : EOF;
    if (c == '\n') {
        ++here_.line;
        here_.column = 1;
    } else if (c != EOF) {
        ++here_.column;
    }
    return c;
}

const Token& Lexer::peek() {
    if (!peeked_) peeked_ = scan();
    return *peeked_;
}

Token Lexer::next() {
    Token token = peek();
    peeked_.reset();
    return token;
}

Token Lexer::scan() {
    std::streambuf* buf = in_.rdbuf();
    auto look = [buf] { return buf ? buf->sgetc() : EOF; };
    // Skip whitespace and comments.
    for (;;) {
        const int c = look();
        if (c == '#') {
            while (look() != EOF && look() != '\n') get();
        } else if (c != EOF && is_space(c)) {
            get();
        } else {
            break;
        }
    }
    Token token;
    token.where = here_;
    if (look() == EOF) {
        token.end = true;
        return token;
    }
    if (look() == '"') {
        get();
        token.quoted = true;
        for (;;) {
            const int c = get();
            if (c == EOF || c == '\n') fail(token.where, "unterminated quoted path");
            if (c == '"') break;
            if (token.text.size() >= kMaxTokenLength)
                fail(token.where,
                     "quoted path longer than " + std::to_string(kMaxTokenLength) + " characters");
            token.text.push_back(static_cast<char>(c));
        }
        return token;
    }
    while (look() != EOF && !is_space(look()) && look() != '#') {
        if (token.text.size() >= kMaxTokenLength)
            fail(token.where,
                 "token longer than " + std::to_string(kMaxTokenLength) + " characters");
        token.text.push_back(static_cast<char>(get()));
    }
    return token;
}

}  // namespace rt
