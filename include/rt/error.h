// The one exception type that carries a user-facing error out to main(), and the place in a
// scene that its message names.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace rt {

// Where a token starts in a scene: what every message about a scene points at. 64-bit
// counters: a line of more than 2^31 bytes must not wrap into negative columns.
struct Location {
    std::int64_t line = 1;
    std::int64_t column = 1;
    int file = 0;  // which of the lexer's file names: 0 is the input's own, others come from
                   // `#line N "path"` markers
};

// A scene, texture or output error. what() is the complete message, already prefixed with
// "file:line:col: " where the error has a place in a scene file. main() prints it and
// exits with status 1.
class Error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

}  // namespace rt
