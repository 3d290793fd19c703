// rtimg info FILE: what an image is, what made it, and the range of each channel.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <optional>

#include "common/message_text.h"
#include "rt/error.h"
#include "rt/image_merge.h"
#include "rtimg.h"

namespace rtimg {

namespace {

std::string number(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", v);
    return buffer;
}

const char* channel_names(int channels, int c) {
    static const char* const names[4][4] = {
        {"grey"}, {"grey", "alpha"}, {"red", "green", "blue"}, {"red", "green", "blue", "alpha"}};
    return names[channels - 1][c];
}

}  // namespace

int info(const std::vector<std::string>& args) {
    const Arguments a = parse_arguments(args, {}, {});
    if (a.files.size() != 1) throw UsageError{"info needs one image: rtimg info FILE"};
    const rt::ImageFile f = rt::read_image_file(a.files[0]);
    // The name and the metadata are shown escaped, one line each: an image's text chunks can
    // hold anything, terminal escape sequences and newlines included.
    const auto shown = [](const std::string& text) { return rt::show_token(text, rt::kShowWhole); };
    std::cout << "file: " << shown(a.files[0]) << "\n"
              << "format: " << rt::format_name(f.format) << " (" << f.variant << ")\n"
              << "size: " << f.width() << "x" << f.height() << "\n"
              << "bit depth: " << f.bits() << (f.format == rt::ImageFormat::pfm ? " (float)" : "")
              << ", " << f.channels() << (f.channels() == 1 ? " channel" : " channels") << "\n";
    // A malformed record does not keep the image from being described: it is said where the
    // region goes, and warned about with the file's name.
    std::optional<rt::RecordedRegion> region;
    std::string problem;
    try {
        region = rt::recorded_region(f);
    } catch (const rt::Error& e) {
        problem = e.what();
    }
    if (!problem.empty()) {
        std::cerr << "rtimg: warning: " << rt::printable_message(a.files[0] + " " + problem)
                  << "\n";
        std::cout << "region: unreadable (" << shown(problem) << ")\n";
    } else if (region)
        std::cout << "region: " << region->rect.x0 << "," << region->rect.x1 << ","
                  << region->rect.y0 << "," << region->rect.y1 << " of a " << region->full_width
                  << "x" << region->full_height << " image\n";
    else
        std::cout << "region: none (a whole image)\n";
    const std::string* software = f.metadata.find("Software");
    std::cout << "made by: " << (software ? shown(*software) : "unknown") << "\n";
    for (const auto& [key, value] : f.metadata.entries)
        if (key != "Software" && key != rt::kRegionKey && key != rt::kFullSizeKey)
            std::cout << shown(key) << ": " << shown(value) << "\n";
    // Samples as stored (0 to 255 or 65535), or PFM's floats.
    std::cout << "channel  min  max  mean\n";
    for (int c = 0; c < f.channels(); ++c) {
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        // Samples are whole numbers below 2^16, so a double sums 2^37 of them exactly; PFM's
        // floats are summed with the error of each addition kept (Neumaier).
        double sum = 0, compensation = 0;
        for (int y = 0; y < f.height(); ++y)
            for (int x = 0; x < f.width(); ++x) {
                const double v = f.format == rt::ImageFormat::pfm
                                     ? f.value(x, y, c)
                                     : static_cast<double>(f.samples.sample(x, y, c));
                lo = std::min(lo, v);
                hi = std::max(hi, v);
                const double t = sum + v;
                compensation += std::fabs(sum) >= std::fabs(v) ? (sum - t) + v : (v - t) + sum;
                sum = t;
            }
        const double total = std::isfinite(sum + compensation) ? sum + compensation : sum;
        const double mean =
            total / (static_cast<double>(f.width()) * static_cast<double>(f.height()));
        std::cout << channel_names(f.channels(), c) << "  " << number(lo) << "  " << number(hi)
                  << "  " << number(mean) << "\n";
    }
    std::cout.flush();
    if (!std::cout) throw std::runtime_error("cannot write to standard output");
    return kExitOk;
}

}  // namespace rtimg
