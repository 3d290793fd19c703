// CRC-32 and Adler-32, the checksums of PNG chunks and of zlib streams.
#include <array>

#include "image/deflate.h"

namespace rt {

namespace {

constexpr std::array<std::uint32_t, 256> make_crc_table() {
    std::array<std::uint32_t, 256> table{};
    for (std::uint32_t n = 0; n < 256; ++n) {
        std::uint32_t c = n;
        for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        table[n] = c;
    }
    return table;
}

constexpr std::array<std::uint32_t, 256> kCrcTable = make_crc_table();

}  // namespace

std::uint32_t crc32(std::string_view data, std::uint32_t crc) {
    crc = ~crc;
    for (const char byte : data)
        crc = kCrcTable[(crc ^ static_cast<unsigned char>(byte)) & 0xFF] ^ (crc >> 8);
    return ~crc;
}

std::uint32_t adler32(std::string_view data, std::uint32_t adler) {
    constexpr std::uint32_t kModulus = 65521;
    // 5552 is the most bytes whose sums cannot overflow 32 bits before the reduction.
    constexpr std::size_t kBlock = 5552;
    std::uint32_t a = adler & 0xFFFF;
    std::uint32_t b = adler >> 16;
    for (std::size_t start = 0; start < data.size(); start += kBlock) {
        const std::size_t end = std::min(data.size(), start + kBlock);
        for (std::size_t i = start; i < end; ++i) {
            a += static_cast<unsigned char>(data[i]);
            b += a;
        }
        a %= kModulus;
        b %= kModulus;
    }
    return (b << 16) | a;
}

}  // namespace rt
