// The image being rendered: doubles, spectral components of a pixel stored together, rows
// from the top, as section 1.5 of the original lays it out.
#pragma once

#include <cstddef>
#include <vector>

#include "rt/spectrum.h"

namespace rt {

class Raster {
  public:
    Raster(int width, int height)
        : width_(width),
          height_(height),
          values_(static_cast<std::size_t>(width) * height * kSpectrumComponents, 0.0) {}

    int width() const { return width_; }
    int height() const { return height_; }

    Spectrum at(int x, int y) const {
        Spectrum s;
        for (std::size_t i = 0; i < kSpectrumComponents; ++i) s[i] = values_[index(x, y) + i];
        return s;
    }
    void set(int x, int y, const Spectrum& s) {
        for (std::size_t i = 0; i < kSpectrumComponents; ++i) values_[index(x, y) + i] = s[i];
    }

  private:
    std::size_t index(int x, int y) const {
        return (static_cast<std::size_t>(y) * width_ + x) * kSpectrumComponents;
    }

    int width_;
    int height_;
    std::vector<double> values_;
};

}  // namespace rt
