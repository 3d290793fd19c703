// SHA-256 (FIPS 180-4): what identifies a render's inputs in a checkpoint (the scene's bytes,
// every texture and mesh file), so that a resume never mixes pixels of another input in.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace rt {

class Sha256 {
  public:
    Sha256();
    void update(std::string_view bytes);
    // The digest of everything given; the object is spent afterwards.
    std::array<std::uint8_t, 32> finish();

  private:
    void block(const std::uint8_t* data);

    std::array<std::uint32_t, 8> state_;
    std::array<std::uint8_t, 64> pending_{};
    std::size_t pending_size_ = 0;
    std::uint64_t total_ = 0;  // bytes given so far
};

// The digest of `bytes` as 64 lowercase hexadecimal digits.
std::string sha256_hex(std::string_view bytes);
// The same for a digest already computed.
std::string to_hex(const std::array<std::uint8_t, 32>& digest);
// The digest of a file's bytes; throws rt::Error naming the file when it cannot be read.
std::string sha256_file_hex(const std::filesystem::path& path);

}  // namespace rt
