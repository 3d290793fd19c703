// Binary PPM (and PGM) output, with the metadata as comment lines after the magic number.
#include "rt/error.h"
#include "rt/image_io.h"

namespace rt {

std::string encode_ppm(const SampleImage& image, const ImageMetadata& metadata) {
    if (image.channels != 3 && image.channels != 1)
        throw Error("PPM stores RGB or grey images, not " + std::to_string(image.channels) +
                    " channels");
    std::string out = image.channels == 3 ? "P6\n" : "P5\n";
    for (const auto& [key, value] : metadata.entries) {
        out += "# " + key + ": ";
        // A comment ends at the line's end, so a value cannot hold one.
        for (const char c : value) out += c == '\n' || c == '\r' ? ' ' : c;
        out += '\n';
    }
    out += std::to_string(image.width) + ' ' + std::to_string(image.height) + '\n' +
           std::to_string(image.max_value()) + '\n';
    out.append(image.bytes.begin(), image.bytes.end());
    return out;
}

}  // namespace rt
