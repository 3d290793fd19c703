// The image being rendered: doubles, spectral components of a pixel stored together, rows
// from the top, as section 1.5 of the original lays it out.
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

#include "rt/large_pages.h"
#include "rt/spectrum.h"

namespace rt {

// A rectangle of pixels: columns [x0, x1), rows [y0, y1), in the full image's coordinates.
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    bool empty() const { return x1 <= x0 || y1 <= y0; }
    bool contains(const PixelRect& r) const {
        return r.x0 >= x0 && r.y0 >= y0 && r.x1 <= x1 && r.y1 <= y1;
    }
    bool operator==(const PixelRect&) const = default;
};

class Raster {
  public:
    // Every pixel black.
    Raster(int width, int height)
        : width_(width),
          height_(height),
          values_(static_cast<std::size_t>(width) * height * kSpectrumComponents) {
        if (!arrays_come_zeroed(values_.size() * sizeof(double)))
            std::fill(values_.begin(), values_.end(), 0.0);
    }

    int width() const { return width_; }
    int height() const { return height_; }

    Spectrum at(int x, int y) const {
        Spectrum s;
        for (std::size_t i = 0; i < kSpectrumComponents; ++i) s[i] = values_[index(x, y) + i];
        return s;
    }
    // Every component, row after row (3 per pixel).
    std::span<const double> values() const { return values_; }
    void set(int x, int y, const Spectrum& s) {
        for (std::size_t i = 0; i < kSpectrumComponents; ++i) values_[index(x, y) + i] = s[i];
    }
    // Pixels x0, x0 + 1, ... of row y from `values`, laid out as values() (3 per pixel).
    void set_row(int y, int x0, std::span<const double> values) {
        std::copy(values.begin(), values.end(),
                  values_.begin() + static_cast<std::ptrdiff_t>(index(x0, y)));
    }

  private:
    std::size_t index(int x, int y) const {
        return (static_cast<std::size_t>(y) * width_ + x) * kSpectrumComponents;
    }

    int width_;
    int height_;
    // 24 MiB at 1024 x 1024: in 2 MiB pages where the kernel offers them, which are faulted
    // in and zeroed several times faster than 4 KiB ones (rt/large_pages.h). Fresh pages are
    // zero already, so they are not written here: the render's threads, writing their rows,
    // are the first to touch them and share the kernel's zeroing (on this machine 24 MiB of
    // fresh memory took some 15 ms on one thread).
    std::vector<double, UninitializedAllocator<double>> values_;
};

}  // namespace rt
