#include "scene/texture.h"

#include <cmath>
#include <string>

#include "common/message_text.h"
#include "rt/error.h"
#include "rt/image_file.h"
#include "scene/input_file.h"

namespace rt {

namespace {

// The file's colours. PPM and PNG samples are divided by the maximum value (in double, as rt
// has always scaled PPM samples); grey stands for all three colours; alpha is not colour and
// is left out.
Image colours(ImageFile file) {
    Image image;
    image.width = file.width();
    image.height = file.height();
    if (file.format == ImageFormat::pfm) {
        // Values above 1 are kept, as a simple surface's colour may exceed 1; anything that is
        // no colour there is none here either.
        for (std::size_t i = 0; i < file.floats.size(); ++i)
            if (!(file.floats[i] >= 0) || !std::isfinite(file.floats[i])) {
                const std::size_t pixel = i / 3;
                throw Error("PFM value " + format_number(file.floats[i]) + " at column " +
                            std::to_string(pixel % static_cast<std::size_t>(image.width)) +
                            ", row " +
                            std::to_string(pixel / static_cast<std::size_t>(image.width)) +
                            " from the top is no colour (each must be finite and >= 0)");
            }
        image.values = std::move(file.floats);
        return image;
    }
    const SampleImage& samples = file.samples;
    const double scale = 1.0 / static_cast<double>(file.full_sample());
    image.values.resize(static_cast<std::size_t>(image.width) * image.height * 3);
    float* out = image.values.data();
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c)
                *out++ = static_cast<float>(
                    static_cast<double>(samples.sample(x, y, samples.channels <= 2 ? 0 : c)) *
                    scale);
    return image;
}

}  // namespace

Image read_texture(const std::filesystem::path& path) {
    std::string bytes = read_regular_file(path);
    // PPM samples as the file has them, so that each is divided by the file's own maximum.
    ImageFile file = decode_image(bytes, PpmSamples::as_stored);
    std::string().swap(bytes);  // freed before the colours are made, to lower the peak
    return colours(std::move(file));
}

std::shared_ptr<const Image> TextureCache::load(const std::filesystem::path& resolved) {
    const FileId file = regular_file_id(resolved);
    if (const auto known = images_.find(file); known != images_.end()) return known->second;
    auto image = std::make_shared<const Image>(read_texture(resolved));
    images_.emplace(file, image);
    return image;
}

}  // namespace rt
