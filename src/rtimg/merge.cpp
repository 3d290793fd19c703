// rtimg merge PIECES... -o FULL: the regions rt --region rendered, put back together.
#include <iostream>

#include "rt/image_merge.h"
#include "rtimg.h"

namespace rtimg {

int merge(const std::vector<std::string>& args) {
    const Arguments a = parse_arguments(args, {"--output"}, {});
    if (!a.has("--output")) throw UsageError{"merge needs -o FULL, the file to write"};
    if (a.files.empty()) throw UsageError{"merge needs the pieces: rtimg merge PIECES... -o FULL"};
    const std::string& output = a.values.at("--output");
    output_format(output);  // a bad name fails before the pieces are read
    std::vector<rt::ImagePiece> pieces;
    std::vector<std::filesystem::path> inputs;
    for (const std::string& file : a.files) {
        pieces.push_back({file, rt::read_image_file(file)});
        inputs.emplace_back(file);
    }
    const rt::ImageFile full = rt::merge_pieces(pieces);
    write_samples(output, full.samples, full.metadata, full.variant == "P3" || full.variant == "P2",
                  inputs);
    return kExitOk;
}

}  // namespace rtimg
