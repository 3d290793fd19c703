// PFM output: the raster's values as 32-bit floats, unclamped and without gamma.
#include <bit>

#include "rt/image_io.h"

namespace rt {

std::string encode_pfm(const Raster& raster) {
    // A negative scale says little-endian. The format lists rows from the bottom.
    std::string out = "PF\n" + std::to_string(raster.width()) + ' ' +
                      std::to_string(raster.height()) + "\n-1.0\n";
    const std::size_t header = out.size();
    out.resize(header + static_cast<std::size_t>(raster.width()) * raster.height() * 12);
    char* p = out.data() + header;
    for (int y = raster.height() - 1; y >= 0; --y)
        for (int x = 0; x < raster.width(); ++x) {
            const Spectrum s = raster.at(x, y);
            for (std::size_t i = 0; i < 3; ++i) {
                const auto bits = std::bit_cast<std::uint32_t>(static_cast<float>(s[i]));
                for (int shift = 0; shift < 32; shift += 8) *p++ = static_cast<char>(bits >> shift);
            }
        }
    return out;
}

}  // namespace rt
