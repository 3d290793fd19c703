// The command line: parsing is separate from main() so that tests can check it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/option_reader.h"
#include "rt/image_io.h"
#include "rt/options.h"

namespace rt {

// An image size given on the command line (--size WxH).
struct ImageSize {
    int width = 0;
    int height = 0;
};

struct CommandLine {
    RenderOptions render;
    std::optional<ImageSize> size;  // overrides the viewer's resolution
    // --region: render only these pixels of the full image; checked against its size once
    // the scene is read (region_problem).
    std::optional<PixelRect> region;
    std::string input = "-";   // the scene; "-" is standard input
    std::string output = "-";  // the image; "-" is standard output
    // The file's format (from -f, else the output's extension, else PPM), bits and gamma;
    // its metadata is filled in from the rest by image_metadata().
    ImageEncoding image;
    bool format_given = false;  // -f was given (else the format comes from -o's name)
    bool metadata = true;       // --no-metadata turns it off
    std::string depfile;        // -M: where to write a make rule; empty for none
    // --checkpoint: where finished rows are kept while rendering; empty for none. --resume
    // continues from what it holds.
    std::string checkpoint;
    bool resume = false;
    bool read_only = false;
    bool quiet = false;     // -q: nothing on stderr but errors
    bool progress = false;  // --progress: progress lines even when stderr is not a terminal
    bool stats = false;     // --stats: statistics on stderr at the end
    bool help = false;
    bool version = false;
};

// Throws UsageError for anything it cannot make sense of.
CommandLine parse_command_line(const std::vector<std::string>& args);

// What the image file records about what made it: "Software" (rt and its version), "Scene"
// (the scene file as named, "<stdin>" for standard input) and "Options" (every option that
// changes pixels, with its value, defaults included), or nothing under --no-metadata.
ImageMetadata image_metadata(const CommandLine& cl);

// What identifies a render for its checkpoint, besides the digests of what it reads: rt's
// version, the image's size, the region rendered and every option that changes pixels (not
// -j, --no-bvh or the output's format, bits and gamma, which leave the raster as it is), as
// "key: value" pairs in a fixed order.
std::vector<std::pair<std::string, std::string>> render_identity(const CommandLine& cl,
                                                                 int width, int height,
                                                                 const PixelRect& region);

// Why --region does not fit a width x height image, or nothing when it fits.
std::optional<std::string> region_problem(const PixelRect& region, int width, int height);

// The metadata a region's file records besides image_metadata, always (rtimg merge needs it):
// kRegionKey ("Region") -> "x0,x1,y0,y1" and kFullSizeKey ("Full-Size") -> "WxH", the full
// image's size.
void add_region_metadata(ImageMetadata& metadata, const PixelRect& region, int width, int height);

// The text of --help.
const char* usage_text();

}  // namespace rt
