// Where things are in the readable sources: positions, the files they name (with the place each
// was included from), and the one error type, whose message carries the "included from" chain.
#pragma once

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "rt/error.h"

namespace rtpp {

struct SourcePos {
    int file = -1;  // an index into SourceFiles; -1 for no place (command-line errors)
    int line = 1;
    int column = 1;
};

struct SourceFile {
    std::string name;            // as messages and line markers show it
    std::filesystem::path path;  // as opened, for resolving includes against its directory
    SourcePos included_from;     // file -1 for the top-level file
};

class SourceFiles {
  public:
    int add(SourceFile file) {
        files_.push_back(std::move(file));
        return static_cast<int>(files_.size() - 1);
    }
    const SourceFile& operator[](int index) const {
        return files_[static_cast<std::size_t>(index)];
    }
    // Counts `size` bytes more of source read (every file each time it is read) against
    // `limit`: false, counting nothing, when they would pass it.
    bool count_text(std::size_t size, std::size_t limit) {
        if (size > limit - std::min(text_read_, limit)) return false;
        text_read_ += size;
        return true;
    }
    // The includes read so far, which Limits::includes bounds.
    long includes_read = 0;

    // "name:line:col".
    std::string place(SourcePos pos) const;
    // The message, prefixed by its place, then one "  included from name:line:col" line for
    // each include that led to the file.
    std::string describe(SourcePos pos, const std::string& message) const;

  private:
    std::vector<SourceFile> files_;
    std::size_t text_read_ = 0;
};

// A user-facing error: what() is complete, place and include chain included. An rt::Error,
// so that main() prints it as it prints OutputFile's.
class CompileError : public rt::Error {
  public:
    using rt::Error::Error;
};

// Thrown below the compiler, which adds the place (the source files are its to describe).
struct SourceError {
    SourcePos pos;
    std::string message;
    // Where the error happened besides its place, innermost first: each loop it was inside,
    // with the loop variable's value then ("for i = 0 to 9" at 3:1, i = 4).
    std::vector<std::pair<SourcePos, std::string>> notes;
};

[[noreturn]] inline void fail(SourcePos pos, std::string message) {
    throw SourceError{pos, std::move(message), {}};
}

}  // namespace rtpp
