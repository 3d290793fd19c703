// Reads a readable scene into statements. `include "file"` is resolved here, once, against
// the including file's directory and then the search path, so the program the evaluator
// runs is one tree; an include cycle or an include nested too deep is an error at the
// include that closes it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rtpp/ast.h"
#include "rtpp/limits.h"
#include "rtpp/source.h"

namespace rtpp {

struct ParseOptions {
    std::vector<std::filesystem::path> include_dirs;  // -I, in order
    Limits limits;
};

// Parses `text` as the top-level file `name` (its includes are resolved against `dir`).
Block parse_program(const std::string& text, const std::string& name,
                    const std::filesystem::path& dir, SourceFiles& files,
                    const ParseOptions& options);

// Words that are the language's own and cannot name a value.
bool is_reserved_word(const std::string& word);

}  // namespace rtpp
