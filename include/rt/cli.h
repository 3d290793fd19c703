// The command line: parsing is separate from main() so that tests can check it.
#pragma once

#include <string>
#include <vector>

#include "rt/image_io.h"
#include "rt/options.h"

namespace rt {

struct CommandLine {
    RenderOptions render;
    std::string input = "-";   // the scene; "-" is standard input
    std::string output = "-";  // the image; "-" is standard output
    // The file's format (from -f, else the output's extension, else PPM), bits and gamma;
    // its metadata is filled in from the rest by image_metadata().
    ImageEncoding image;
    bool metadata = true;  // --no-metadata turns it off
    bool read_only = false;
    bool help = false;
    bool version = false;
};

// Throws UsageError for anything it cannot make sense of.
struct UsageError {
    std::string message;
};

CommandLine parse_command_line(const std::vector<std::string>& args);

// What the image file records about what made it: "Software" (rt and its version), "Scene"
// (the scene file as named, "<stdin>" for standard input) and "Options" (every option that
// changes pixels, with its value, defaults included), or nothing under --no-metadata.
ImageMetadata image_metadata(const CommandLine& cl);

// The text of --help.
const char* usage_text();

}  // namespace rt
