// Textures, the images image-mapped surfaces (108) wear: read through the image library (PNG,
// PPM or PGM, PFM, as the file's first bytes say), from regular files only.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <vector>

#include "rt/spectrum.h"
#include "scene/input_file.h"

namespace rt {

// A texture's colours, rows from the top: PPM and PNG samples divided by the file's maximum
// value, PFM values as they are (docs/format.md, 108).
struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> values;  // width * height * 3

    Spectrum at(int x, int y) const {
        const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
        return {values[i], values[i + 1], values[i + 2]};
    }
};

// Reads a texture from a regular file; throws rt::Error("<reason>") without a location, which
// the caller adds.
Image read_texture(const std::filesystem::path& path);

// The textures one scene has loaded: each file once, however many surfaces name it, by
// whatever path.
class TextureCache {
  public:
    // The texture at `resolved`, read the first time its file is named; throws
    // rt::Error("<reason>") as read_texture does.
    std::shared_ptr<const Image> load(const std::filesystem::path& resolved);
    std::size_t files() const { return images_.size(); }

  private:
    std::map<FileId, std::shared_ptr<const Image>> images_;  // by file, not by name
};

}  // namespace rt
