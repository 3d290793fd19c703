// Checksums and the deflate compressed format (RFC 1950, 1951), written for PNG: rt uses
// nothing beyond the standard library, so it carries its own.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace rt {

// CRC-32 as PNG and zlib use it (polynomial 0xEDB88320, reflected). Pass a previous result
// as `crc` to continue over more data.
std::uint32_t crc32(std::string_view data, std::uint32_t crc = 0);

// Adler-32 (RFC 1950). Pass a previous result as `adler` to continue over more data.
std::uint32_t adler32(std::string_view data, std::uint32_t adler = 1);

// Optimal prefix code lengths of at most `limit` bits for the symbols' frequencies
// (package-merge); a symbol of frequency 0 gets 0, a lone symbol 1. Needs 2^limit >= the
// number of symbols in use.
std::vector<std::uint8_t> huffman_code_lengths(const std::vector<std::uint32_t>& freq, int limit);

// A raw deflate stream of `data`: LZ77 over a 32 KiB window with hash chains and lazy
// matching (zlib's level-6 parameters), and per block the smallest of dynamic Huffman codes
// (limited to 15 bits), the fixed codes, or stored bytes.
std::string deflate(std::string_view data);

// Decodes a raw deflate stream up to its last block. Throws rt::Error when the stream is
// malformed or ends early, or when it would decode to more than `max_size` bytes (so a small
// hostile file cannot claim gigabytes). `consumed`, when given, receives the number of input
// bytes the stream took.
std::string inflate(std::string_view data, std::size_t max_size, std::size_t* consumed = nullptr);

// The zlib format (RFC 1950): a two-byte header, the deflate stream, Adler-32 of the data.
std::string zlib_compress(std::string_view data);
// Throws rt::Error for a malformed stream, a wrong checksum or more than `max_size` bytes.
std::string zlib_decompress(std::string_view data, std::size_t max_size);

}  // namespace rt
