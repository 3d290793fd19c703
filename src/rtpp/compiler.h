// The whole of rtpp as a library call: readable source in, numeric scene out.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rtpp/limits.h"
#include "rtpp/source.h"  // CompileError

namespace rtpp {

struct CompileOptions {
    std::vector<std::filesystem::path> include_dirs;  // searched after the including file's own
    Limits limits;
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
