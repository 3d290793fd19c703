// The constants of the deflate format (RFC 1951, section 3.2.5), shared by the encoder and
// the decoder.
#pragma once

#include <array>
#include <cstdint>

namespace rt::deflate_format {

inline constexpr int kMinMatch = 3;
inline constexpr int kMaxMatch = 258;
inline constexpr int kWindowSize = 32768;
inline constexpr int kEndOfBlock = 256;
inline constexpr int kLiteralLengthCodes = 286;  // 0-255 literals, 256 end, 257-285 lengths
inline constexpr int kDistanceCodes = 30;
inline constexpr int kCodeLengthCodes = 19;
inline constexpr int kMaxCodeBits = 15;
inline constexpr int kMaxCodeLengthBits = 7;

// Lengths 3-258 as codes 257-285: the shortest length of each code and its extra bits.
inline constexpr std::array<std::uint16_t, 29> kLengthBase = {
    3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
    31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
inline constexpr std::array<std::uint8_t, 29> kLengthExtra = {
    0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};

// Distances 1-32768 as codes 0-29.
inline constexpr std::array<std::uint16_t, 30> kDistanceBase = {
    1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,   65,    97,    129,
    193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
inline constexpr std::array<std::uint8_t, 30> kDistanceExtra = {
    0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
    6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};

// The order in which a dynamic block lists the code-length code's lengths.
inline constexpr std::array<std::uint8_t, 19> kCodeLengthOrder = {
    16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15};

// The fixed literal/length code's bit lengths (block type 1); every fixed distance code has 5.
inline constexpr int fixed_literal_length_bits(int symbol) {
    return symbol < 144 ? 8 : symbol < 256 ? 9 : symbol < 280 ? 7 : 8;
}
inline constexpr int kFixedDistanceBits = 5;

// Huffman codes are defined most significant bit first but packed from the least
// significant end, so both sides use them bit-reversed.
inline constexpr int reverse_bits(int code, int length) {
    int reversed = 0;
    for (int b = 0; b < length; ++b) reversed |= ((code >> b) & 1) << (length - 1 - b);
    return reversed;
}

}  // namespace rt::deflate_format
