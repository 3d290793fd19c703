// How two images differ: the statistics rtimg diff prints and the golden-image test judges
// by, and a heat map that shows where they differ.
#pragma once

#include <cstddef>

#include "rt/image_file.h"

namespace rt {

// Differences are in 8-bit levels (255 is full intensity), over red, green and blue (grey
// counts as all three; alpha is left out), whatever the files' bit depths.
struct ImageDifference {
    double largest = 0;         // the largest difference of one component
    std::size_t pixels = 0;     // width x height
    std::size_t differing = 0;  // pixels with a component more than the tolerance apart
    double mean_absolute = 0;   // over every component of every pixel
    double rms = 0;             // root of the mean squared difference
    double psnr = 0;            // 20 log10(255 / rms) in dB; infinite when rms is 0

    double fraction() const {
        return pixels == 0 ? 0 : static_cast<double>(differing) / static_cast<double>(pixels);
    }
};

// a and b must have the same size (std::invalid_argument otherwise).
ImageDifference compare_images(const ImageFile& a, const ImageFile& b, double tolerance);

// An RGB 8-bit image of a's size: a pixel within the tolerance shows a, darkened to a quarter
// and grey, for orientation; one that differs but within the tolerance is dark blue; one
// beyond it is red, from 96 to 255 as its largest difference goes from the tolerance to 64
// levels above it.
SampleImage heat_map(const ImageFile& a, const ImageFile& b, double tolerance);

}  // namespace rt
