// Where a token starts in a scene: what every message about a scene points at.
#pragma once

#include <cstdint>

namespace rt {

// 64-bit counters: a line of more than 2^31 bytes must not wrap into negative columns.
struct Location {
    std::int64_t line = 1;
    std::int64_t column = 1;
    int file = 0;  // which of the lexer's file names: 0 is the input's own, others come from
                   // `#line N "path"` markers
};

}  // namespace rt
