// PFM input: colour (PF) or grey (Pf) 32-bit floats, either byte order, rows from the bottom.
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>

#include "common/ascii.h"
#include "common/message_text.h"
#include "rt/error.h"
#include "rt/image_file.h"
#include "rt/limits.h"

namespace rt {

namespace {

// One whitespace-separated header field from `at`, which moves past the field and the single
// whitespace character after it.
std::string_view field(std::string_view s, std::size_t& at) {
    while (at < s.size() && is_ascii_space(s[at])) ++at;
    const std::size_t start = at;
    while (at < s.size() && !is_ascii_space(s[at])) ++at;
    if (start == at || at == s.size()) throw Error("PFM header ends early");
    const std::string_view text = s.substr(start, at - start);
    ++at;
    return text;
}

template <typename T>
T parse(std::string_view text, const char* what) {
    T value{};
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || ptr != text.data() + text.size())
        throw Error(std::string("PFM file has no valid ") + what);
    return value;
}

}  // namespace

ImageFile decode_pfm(std::string_view file) {
    std::size_t at = 0;
    const std::string_view magic = field(file, at);
    if (magic != "PF" && magic != "Pf") throw Error("not a PFM file (expected PF or Pf)");
    const int width = parse<int>(field(file, at), "width");
    const int height = parse<int>(field(file, at), "height");
    const std::string_view text_of_scale = field(file, at);
    const double scale = parse<double>(text_of_scale, "scale");
    if (width < 1 || height < 1) throw Error("PFM image has no pixels");
    if (static_cast<long>(width) * height > kMaxImagePixels)
        throw Error("PFM image is larger than " + std::to_string(kMaxImagePixels) + " pixels");
    // The scale's sign gives the byte order, so only a finite number other than 0 is one (a
    // NaN has no sign to trust).
    if (!std::isfinite(scale) || scale == 0)
        throw Error("PFM scale must be a finite number other than 0, got " +
                    std::string(quote_token(text_of_scale, 40)));
    const bool little = scale < 0;
    const int stored = magic == "PF" ? 3 : 1;
    const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (file.size() - at < pixels * stored * 4) throw Error("PFM pixel data ends early");
    ImageFile image;
    image.format = ImageFormat::pfm;
    image.variant = std::string(magic);
    image.samples.width = width;
    image.samples.height = height;
    image.samples.channels = 3;
    image.floats.resize(pixels * 3);
    const auto* p = reinterpret_cast<const unsigned char*>(file.data() + at);
    for (int row = height - 1; row >= 0; --row)  // the file starts with the bottom row
        for (int x = 0; x < width; ++x) {
            float v[3] = {};
            for (int c = 0; c < stored; ++c, p += 4) {
                std::uint32_t bits = 0;
                for (int b = 0; b < 4; ++b) bits |= std::uint32_t{p[little ? b : 3 - b]} << (8 * b);
                v[c] = std::bit_cast<float>(bits);
            }
            if (stored == 1) v[1] = v[2] = v[0];
            std::memcpy(&image.floats[(static_cast<std::size_t>(row) * width + x) * 3], v,
                        sizeof v);
        }
    return image;
}

}  // namespace rt
