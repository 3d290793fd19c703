// Binary PPM (and PGM) output, with the metadata as comment lines after the magic number.
#include "common/message_text.h"
#include "rt/error.h"
#include "rt/image_file.h"
#include "rt/image_io.h"

namespace rt {

bool ppm_key(std::string_view key) {
    if (key.empty()) return false;
    for (const char ch : key) {
        const auto c = static_cast<unsigned char>(ch);
        if (c <= ' ' || c == 127) return false;
    }
    return true;
}

std::string encode_ppm(const SampleImage& image, const ImageMetadata& metadata) {
    std::string out = ppm_header(image, metadata);
    out.append(image.bytes.begin(), image.bytes.end());
    return out;
}

std::string ppm_header(const SampleImage& image, const ImageMetadata& metadata) {
    if (image.channels != 3 && image.channels != 1)
        throw Error("PPM stores RGB or grey images, not " + std::to_string(image.channels) +
                    " channels");
    std::string out = image.channels == 3 ? "P6\n" : "P5\n";
    for (const auto& [key, value] : metadata.entries) {
        // A key that would not read back (a PNG keyword may hold spaces) is refused, not
        // changed: one with a newline could otherwise write header lines of its own.
        if (!ppm_key(key))
            throw Error(quote_token(key, kShowWhole) +
                        " cannot be a PPM metadata key (one word, no spaces or control "
                        "characters)");
        // A comment ends at the line's end, so a value cannot hold a line break (nor end in
        // a carriage return, which reading takes for a CRLF's): refused, never changed.
        if (value.find_first_of("\r\n") != std::string::npos)
            throw Error("the value of PPM metadata key " + quote_token(key, kShowWhole) +
                        " holds a line break, which a PPM comment cannot hold (PNG can)");
        out += "# " + key + ": " + value + '\n';
    }
    out += std::to_string(image.width) + ' ' + std::to_string(image.height) + '\n' +
           std::to_string(image.max_value()) + '\n';
    return out;
}

}  // namespace rt
