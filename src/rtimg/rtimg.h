// rtimg's commands: each takes its arguments (after the command's name) and returns the exit
// status; main() dispatches and turns exceptions into messages.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "common/exit_status.h"
#include "common/option_reader.h"
#include "rt/image_io.h"

namespace rtimg {

using rt::kExitOk;
using rt::kExitUsage;  // the command line made no sense (diff: any error)
// diff: the images differ too much; the other commands: an error.
inline constexpr int kExitFail = rt::kExitError;

using rt::UsageError;

// Positional arguments and --option values (-o is --output), "--name=value" or "--name value".
struct Arguments {
    std::vector<std::string> files;
    std::map<std::string, std::string> values;
    bool has(const std::string& option) const { return values.count(option) != 0; }
};
// `valued` lists the long options that take a value, `flags` those that take none; anything
// else starting with '-' is a usage error.
Arguments parse_arguments(const std::vector<std::string>& args,
                          const std::vector<std::string>& valued,
                          const std::vector<std::string>& flags);
// A number >= 0 given to `option`, read as rt reads its numbers (a leading '+' allowed).
using rt::parse_nonnegative;
// The format an output file's name asks for (.ppm, .pgm, .png, .pfm).
rt::ImageFormat output_format(const std::string& path);
// Writes samples in the format `path` names (PPM, plain PPM with `plain`, or PNG), safely
// (rt::OutputFile), never over one of `inputs`.
// Whether `path` ends in .pgm; and the image as a file of that name holds it: grey from
// equal channels (refused with a message when it has colour), else as it is.
bool names_pgm(const std::string& path);
rt::SampleImage for_the_name(const std::string& path, rt::SampleImage image);

void write_samples(const std::string& path, const rt::SampleImage& image,
                   const rt::ImageMetadata& metadata, bool plain,
                   const std::vector<std::filesystem::path>& inputs);

int diff(const std::vector<std::string>& args);
int merge(const std::vector<std::string>& args);
int convert(const std::vector<std::string>& args);
int info(const std::vector<std::string>& args);

const char* usage_text();

}  // namespace rtimg
