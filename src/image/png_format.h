// What the PNG writer and reader share (ISO/IEC 15948).
#pragma once

#include <cstdint>
#include <cstdlib>
#include <string_view>

namespace rt::png_format {

inline constexpr std::string_view kSignature{"\x89PNG\r\n\x1a\n", 8};

// Colour types.
inline constexpr int kGrey = 0;
inline constexpr int kRgb = 2;
inline constexpr int kPalette = 3;
inline constexpr int kGreyAlpha = 4;
inline constexpr int kRgbAlpha = 6;

// A keyword as the PNG specification allows it, in Latin-1 (the bytes of the file): 1-79
// printable characters (32-126 and 161-255), no leading, trailing or double spaces.
inline bool valid_keyword(std::string_view key) {
    if (key.empty() || key.size() > 79 || key.front() == ' ' || key.back() == ' ') return false;
    for (std::size_t i = 0; i < key.size(); ++i) {
        const auto c = static_cast<unsigned char>(key[i]);
        if (c < 32 || (c > 126 && c < 161)) return false;
        if (c == ' ' && i + 1 < key.size() && key[i + 1] == ' ') return false;
    }
    return true;
}

// Filter types 0-4: none, sub, up, average, Paeth.
inline constexpr int kFilterTypes = 5;

inline std::uint8_t paeth(std::uint8_t a, std::uint8_t b, std::uint8_t c) {
    const int p = a + b - c;
    const int pa = std::abs(p - a);
    const int pb = std::abs(p - b);
    const int pc = std::abs(p - c);
    return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

// The prediction filter `type` makes for a byte from its left (a), upper (b) and upper-left
// (c) neighbours.
inline std::uint8_t predict(int type, std::uint8_t a, std::uint8_t b, std::uint8_t c) {
    switch (type) {
        case 1:
            return a;
        case 2:
            return b;
        case 3:
            return static_cast<std::uint8_t>((a + b) / 2);
        case 4:
            return paeth(a, b, c);
        default:
            return 0;
    }
}

}  // namespace rt::png_format
