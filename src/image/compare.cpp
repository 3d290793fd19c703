// Image comparison: statistics and the heat map.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "rt/image_compare.h"

namespace rt {

namespace {

void require_same_size(const ImageFile& a, const ImageFile& b) {
    if (a.width() != b.width() || a.height() != b.height())
        throw std::invalid_argument("images of different sizes");
}

// How far apart two components are, in levels. A NaN (in a PFM) is a difference from any
// number, an infinite one, so that no comparison passes it; two NaNs are alike, as two equal
// numbers are (the renders agree on where the value is undefined), and so are two equal
// infinities, whose subtraction alone would give NaN.
double component_difference(double a, double b) {
    if (a == b) return 0;
    const bool a_nan = std::isnan(a), b_nan = std::isnan(b);
    if (a_nan || b_nan) return a_nan && b_nan ? 0 : std::numeric_limits<double>::infinity();
    return std::fabs(a - b);
}

// The largest component difference of pixel (x, y), in levels.
double pixel_difference(const ImageFile& a, const ImageFile& b, int x, int y) {
    double largest = 0;
    for (int c = 0; c < 3; ++c)
        largest = std::max(largest, component_difference(a.level(x, y, c), b.level(x, y, c)));
    return largest;
}

// A sum in double that keeps what each addition rounds off (Neumaier's compensation), so that
// millions of terms lose nothing that shows, the same way on every machine.
class Sum {
  public:
    void add(double v) {
        const double t = total_ + v;
        compensation_ += std::fabs(total_) >= std::fabs(v) ? (total_ - t) + v : (v - t) + total_;
        total_ = t;
    }
    double value() const {
        const double v = total_ + compensation_;
        return std::isnan(v) ? total_ : v;  // inf - inf in the compensation is no NaN
    }

  private:
    double total_ = 0;
    double compensation_ = 0;
};

}  // namespace

ImageDifference compare_images(const ImageFile& a, const ImageFile& b, double tolerance) {
    require_same_size(a, b);
    ImageDifference d;
    d.pixels = static_cast<std::size_t>(a.width()) * static_cast<std::size_t>(a.height());
    Sum sum, sum_squares;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            double pixel = 0;
            for (int c = 0; c < 3; ++c) {
                const double diff = component_difference(a.level(x, y, c), b.level(x, y, c));
                pixel = std::max(pixel, diff);
                sum.add(diff);
                sum_squares.add(diff * diff);
            }
            d.largest = std::max(d.largest, pixel);
            if (pixel > tolerance) ++d.differing;
        }
    const double components = 3.0 * static_cast<double>(d.pixels);
    d.mean_absolute = sum.value() / components;
    d.rms = std::sqrt(sum_squares.value() / components);
    d.psnr = d.rms == 0 ? std::numeric_limits<double>::infinity() : 20 * std::log10(255 / d.rms);
    return d;
}

SampleImage heat_map(const ImageFile& a, const ImageFile& b, double tolerance) {
    require_same_size(a, b);
    SampleImage map{a.width(), a.height(), 3, 8, {}};
    map.bytes.reserve(map.row_bytes() * static_cast<std::size_t>(map.height));
    const auto push = [&](double r, double g, double bl) {
        for (const double v : {r, g, bl})
            map.bytes.push_back(static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 255.0))));
    };
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const double diff = pixel_difference(a, b, x, y);
            if (diff > tolerance) {
                push(96 + 159 * std::min(1.0, (diff - tolerance) / 64), 0, 0);
            } else if (diff > 0) {
                push(0, 0, 128);
            } else {
                const double luma =
                    0.299 * a.level(x, y, 0) + 0.587 * a.level(x, y, 1) + 0.114 * a.level(x, y, 2);
                push(luma / 4, luma / 4, luma / 4);
            }
        }
    return map;
}

}  // namespace rt
