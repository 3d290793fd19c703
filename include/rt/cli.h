// The command line: parsing is separate from main() so that tests can check it.
#pragma once

#include <string>
#include <vector>

#include "rt/options.h"

namespace rt {

struct CommandLine {
    RenderOptions render;
    std::string input = "-";   // the scene; "-" is standard input
    std::string output = "-";  // the image; "-" is standard output
    std::string depfile;       // -M: where to write a make rule; empty for none
    bool read_only = false;
    bool help = false;
    bool version = false;
};

// Throws UsageError for anything it cannot make sense of.
struct UsageError {
    std::string message;
};

CommandLine parse_command_line(const std::vector<std::string>& args);

// The text of --help.
const char* usage_text();

}  // namespace rt
