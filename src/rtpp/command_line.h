// rtpp's command line, parsed apart from main() so that tests can check it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/option_reader.h"
#include "common/output_file.h"
#include "common/spool.h"

namespace rtpp {

// What the input is written in: rtpp's readable language, or NFF (docs/nff.md).
enum class InputFormat { rts, nff };

struct CommandLine {
    std::string input = "-";  // the readable scene; "-" is standard input
    // --from, else NFF for a name ending in ".nff" (any case), else the readable language.
    InputFormat from = InputFormat::rts;
    std::string output = "-";  // the numeric scene; "-" is standard output
    std::vector<std::string> include_dirs;
    std::vector<std::pair<std::string, std::string>> defines;  // -D NAME=VALUE, in order
    bool help = false;
    bool version = false;
};

using rt::UsageError;

CommandLine parse_command_line(const std::vector<std::string>& args);
const char* usage_text();

// Where rtpp writes the numeric scene: standard output for "-" (a terminal too, the scene
// being text), else a file claimed through rt::OutputFile when constructed, before compiling,
// so that a bad path fails fast. The file is replaced only once complete (a temporary file
// of its own beside it, removed on an error or a signal), keeps its mode, and is never the
// scene being compiled; a device or FIFO is written in place. Throws rt::Error.
class SceneOutput {
  public:
    explicit SceneOutput(const CommandLine& cl);

    // Writes the whole scene; returns the exit status.
    int write(const std::string& text);
    int write(rt::Spool& text);

  private:
    std::optional<rt::OutputFile> file_;
};

}  // namespace rtpp
