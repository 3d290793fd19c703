// The whole of rtpp as a library call: readable source in, numeric scene out.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "rtpp/limits.h"
#include "rtpp/source.h"  // CompileError

namespace rtpp {

struct CompileOptions {
    std::vector<std::filesystem::path> include_dirs;  // searched after the including file's own
    Limits limits;
    // -D NAME=VALUE, in order: each VALUE an expression of the language (it may use the
    // names defined before it), bound before the program runs; a top-level `let` of the same
    // name in the program takes the defined value instead of its own, so a scene can give a
    // default that the command line overrides (let frame = 0).
    std::vector<std::pair<std::string, std::string>> defines;
};

// Compiles `text`, named `name` in messages and line markers, whose includes are resolved
// against `dir`. Returns the numeric scene; throws CompileError with the complete message
// (place and "included from" chain).
std::string compile(const std::string& text, const std::string& name,
                    const std::filesystem::path& dir, const CompileOptions& options = {});

// Reads and compiles a file ("-" for standard input, named <stdin>, includes resolved
// against the current directory).
std::string compile_file(const std::string& path, const CompileOptions& options = {});

}  // namespace rtpp
