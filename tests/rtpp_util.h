// Helpers for tests of rtpp's compiler: a camera every test scene can start with, and the
// message a source's (or a file's) compilation fails with.
#pragma once

#include <string>

#include "rtpp/compiler.h"

namespace rtpp_test {

inline const std::string kCamera =
    "camera { position <0, 0, 5> look_at <0, 0, 0> fov 90 size 4, 4 }\n";

// The complete message of the CompileError that compiling `source` (named t.rts, includes
// resolved against the current directory) throws, or "" when it compiles.
inline std::string error_of(const std::string& source, const rtpp::CompileOptions& options = {}) {
    try {
        rtpp::compile(source, "t.rts", ".", options);
    } catch (const rtpp::CompileError& e) {
        return e.what();
    }
    return "";
}

// The same for a file compiled with compile_file (its includes resolved against its own
// directory).
inline std::string file_error_of(const std::string& path,
                                 const rtpp::CompileOptions& options = {}) {
    try {
        rtpp::compile_file(path, options);
    } catch (const rtpp::CompileError& e) {
        return e.what();
    }
    return "";
}

}  // namespace rtpp_test
