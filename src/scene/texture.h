// Textures, the images image-mapped surfaces (108) wear: read through the image library (PNG,
// PPM or PGM, PFM, as the file's first bytes say), from regular files only.
#pragma once

#include <compare>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <vector>

#include "rt/spectrum.h"

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

// A file's identity: the same file under any name (links, ./, ..) has the same one.
struct FileId {
    std::uint64_t device = 0;
    std::uint64_t inode = 0;
    auto operator<=>(const FileId&) const = default;
};

// The identity of a texture file, which must be a regular file; throws rt::Error("<reason>")
// otherwise (a FIFO or a device is refused without being opened, so it cannot block).
FileId texture_file(const std::filesystem::path& path);

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
    // Every path named so far, each once, in the order first named.
    const std::vector<std::filesystem::path>& paths() const { return paths_; }
    std::size_t files() const { return images_.size(); }

  private:
    std::map<FileId, std::shared_ptr<const Image>> images_;  // by file, not by name
    std::vector<std::filesystem::path> paths_;
};

}  // namespace rt
