// Files a scene reads besides itself (textures, mesh files): regular files only, read whole,
// each known by its identity so that it is loaded once however it is spelled.
#pragma once

#include <compare>
#include <cstdint>
#include <filesystem>
#include <string>

namespace rt {

// A file's identity: the same file under any name (links, ./, ..) has the same one.
struct FileId {
    std::uint64_t device = 0;
    std::uint64_t inode = 0;
    auto operator<=>(const FileId&) const = default;
};

// The identity of a file, which must be a regular file; throws rt::Error("<reason>")
// otherwise (a FIFO or a device is refused without being opened, so it cannot block).
FileId regular_file_id(const std::filesystem::path& path);

// The bytes of a regular file, as far as the size it had when opened; throws
// rt::Error("<reason>") without a location, which the caller adds.
std::string read_regular_file(const std::filesystem::path& path);

}  // namespace rt
