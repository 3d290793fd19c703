// Reading any image file rt's tools handle, and its values as numbers.
#include "rt/image_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "rt/error.h"

namespace rt {

double ImageFile::value(int x, int y, int c) const {
    const std::size_t pixel = static_cast<std::size_t>(y) * width() + x;
    if (format == ImageFormat::pfm) return floats[pixel * 3 + c];
    return static_cast<double>(samples.sample(x, y, c)) / full_sample();
}

double ImageFile::level(int x, int y, int c) const {
    if (format == ImageFormat::pfm)
        return floats[(static_cast<std::size_t>(y) * width() + x) * 3 + c] * 255.0;
    const int channel = channels() <= 2 ? 0 : c;
    // 8-bit samples are their own levels exactly (s * 255 / 255 rounds to s); others are scaled.
    const double s = samples.sample(x, y, channel);
    return s * 255.0 / full_sample();
}

ImageFile decode_image(std::string_view file, PpmSamples ppm) {
    if (file.size() >= 8 && file.substr(0, 8) == "\x89PNG\r\n\x1a\n") {
        DecodedImage png = decode_png(file);
        ImageFile image;
        image.format = ImageFormat::png;
        image.variant = "PNG";
        image.samples = std::move(png.image);
        image.metadata = std::move(png.metadata);
        return image;
    }
    if (file.size() >= 2 && (file.substr(0, 2) == "PF" || file.substr(0, 2) == "Pf"))
        return decode_pfm(file);
    if (file.size() >= 2 && file[0] == 'P') return decode_ppm(file, ppm);
    throw Error("not an image rt reads (PPM, PGM, PNG or PFM)");
}

ImageFile read_image_file(const std::filesystem::path& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw Error(path.string() + ": it is a directory");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path.string() + ": cannot open it: " + std::strerror(errno));
    std::ostringstream bytes;
    bytes << in.rdbuf();
    try {
        return decode_image(bytes.view());
    } catch (const Error& e) {
        throw Error(path.string() + ": " + e.what());
    }
}

Raster to_raster(const ImageFile& image) {
    Raster raster(image.width(), image.height());
    const int colour = image.channels() <= 2 ? 1 : 3;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            Spectrum s;
            for (int c = 0; c < 3; ++c)
                s[static_cast<std::size_t>(c)] = image.value(x, y, colour == 1 ? 0 : c);
            raster.set(x, y, s);
        }
    return raster;
}

}  // namespace rt
