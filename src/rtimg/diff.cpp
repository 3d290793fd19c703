// rtimg diff A B: how two images differ, and whether that is within the limits given.
#include <cmath>
#include <cstdio>
#include <iostream>

#include "common/message_text.h"
#include "rt/image_compare.h"
#include "rtimg.h"

namespace rtimg {

namespace {

std::string number(double v) {
    // The sign matters: a PSNR of -inf (an infinite difference) is the worst, not the best.
    if (std::isinf(v)) return v < 0 ? "-inf" : "inf";
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", v);
    return buffer;
}

std::string size_text(const rt::ImageFile& f) {
    return std::to_string(f.width()) + "x" + std::to_string(f.height());
}

}  // namespace

int diff(const std::vector<std::string>& args) {
    const Arguments a = parse_arguments(args, {"--tolerance", "--max-fraction", "--output"}, {});
    if (a.files.size() != 2) throw UsageError{"diff needs two images: rtimg diff A B"};
    const double tolerance =
        a.has("--tolerance") ? parse_nonnegative("--tolerance", a.values.at("--tolerance")) : 0;
    const double max_fraction =
        a.has("--max-fraction") ? parse_nonnegative("--max-fraction", a.values.at("--max-fraction"))
                                : 0;
    if (max_fraction > 1)
        throw UsageError{"--max-fraction is a share of the pixels, from 0 to 1, got " +
                         rt::quote_token(a.values.at("--max-fraction"))};
    if (a.has("--output")) output_format(a.values.at("--output"));  // a bad name fails first
    const rt::ImageFile first = rt::read_image_file(a.files[0]);
    const rt::ImageFile second = rt::read_image_file(a.files[1]);
    if (first.width() != second.width() || first.height() != second.height()) {
        std::cout << "size: " << size_text(first) << " and " << size_text(second)
                  << ": different sizes\nresult: fail\n";
        return kExitFail;
    }
    const rt::ImageDifference d = rt::compare_images(first, second, tolerance);
    if (a.has("--output"))
        write_samples(a.values.at("--output"), rt::heat_map(first, second, tolerance), {}, false,
                      {a.files[0], a.files[1]});
    const bool pass = d.fraction() <= max_fraction;
    std::cout << "size: " << size_text(first) << "\n"
              << "largest difference: " << number(d.largest) << " levels\n"
              << "differing pixels: " << d.differing << " of " << d.pixels << " ("
              << number(100 * d.fraction()) << "%) by more than " << number(tolerance)
              << " levels\n"
              << "mean absolute error: " << number(d.mean_absolute) << " levels\n"
              << "RMSE: " << number(d.rms) << " levels\n"
              << "PSNR: " << number(d.psnr) << " dB\n"
              << "result: " << (pass ? "pass" : "fail") << " (share " << number(d.fraction())
              << (pass ? " <= " : " > ") << "--max-fraction " << number(max_fraction) << ")\n";
    std::cout.flush();
    if (!std::cout) throw std::runtime_error("cannot write to standard output");
    return pass ? kExitOk : kExitFail;
}

}  // namespace rtimg
