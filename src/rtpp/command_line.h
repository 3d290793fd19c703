// rtpp's command line, parsed apart from main() so that tests can check it.
#pragma once

#include <string>
#include <vector>

#include "common/option_reader.h"

namespace rtpp {

struct CommandLine {
    std::string input = "-";   // the readable scene; "-" is standard input
    std::string output = "-";  // the numeric scene; "-" is standard output
    std::vector<std::string> include_dirs;
    bool help = false;
    bool version = false;
};

using rt::UsageError;

CommandLine parse_command_line(const std::vector<std::string>& args);
const char* usage_text();

// Writes `text` to `path` ("-": standard output) through a temporary file beside it, so a
// failed run leaves an existing file as it was. Throws CompileError.
void write_output(const std::string& path, const std::string& text);

}  // namespace rtpp
