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

// The largest component difference of pixel (x, y), in levels.
double pixel_difference(const ImageFile& a, const ImageFile& b, int x, int y) {
    double largest = 0;
    for (int c = 0; c < 3; ++c)
        largest = std::max(largest, std::fabs(a.level(x, y, c) - b.level(x, y, c)));
    return largest;
}

}  // namespace

ImageDifference compare_images(const ImageFile& a, const ImageFile& b, double tolerance) {
    require_same_size(a, b);
    ImageDifference d;
    d.pixels = static_cast<std::size_t>(a.width()) * static_cast<std::size_t>(a.height());
    // Sums in long double, row by row, so that 4096^2 images lose nothing to rounding.
    long double sum = 0, sum_squares = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            double pixel = 0;
            for (int c = 0; c < 3; ++c) {
                const double diff = std::fabs(a.level(x, y, c) - b.level(x, y, c));
                pixel = std::max(pixel, diff);
                sum += diff;
                sum_squares += static_cast<long double>(diff) * diff;
            }
            d.largest = std::max(d.largest, pixel);
            if (pixel > tolerance) ++d.differing;
        }
    const long double components = 3.0L * static_cast<long double>(d.pixels);
    d.mean_absolute = static_cast<double>(sum / components);
    d.rms = static_cast<double>(std::sqrt(sum_squares / components));
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
