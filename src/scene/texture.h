// PPM images: the renderer's output (P6) and textures (P6 or P3).
#pragma once

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "rt/limits.h"
#include "rt/raster.h"

namespace rt {

// round(255 * clamp(c, 0, 1)); NaN counts as 0.
std::uint8_t to_byte(double c);

// Writes the raster as binary PPM (P6, maxval 255), without metadata: encode_image with the
// default encoding.
void write_ppm(std::ostream& out, const Raster& raster);

// An image read from a PPM file, components scaled to [0, 1], rows from the top.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> values;  // width * height * 3

    Spectrum at(int x, int y) const {
        const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
        return {values[i], values[i + 1], values[i + 2]};
    }
};

// A file's identity: the same file under any name (links, ./, ..) has the same one.
struct FileId {
    std::uint64_t device = 0;
    std::uint64_t inode = 0;
    auto operator<=>(const FileId&) const = default;
};

// The identity of a texture file, which must be a regular file; throws rt::Error("<reason>")
// otherwise (a FIFO or a device is refused without being opened, so it cannot block).
FileId texture_file(const std::filesystem::path& path);

// Reads a P6 or P3 regular file; throws rt::Error("<reason>") without a location, which the caller
// adds.
Image read_ppm(const std::filesystem::path& path);

}  // namespace rt
