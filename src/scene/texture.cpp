#include "scene/texture.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <istream>

#include "rt/error.h"
#include "common/fd_stream.h"
#include "rt/image_io.h"

namespace rt {

std::uint8_t to_byte(double c) {
    if (!(c > 0)) return 0;  // also catches NaN
    if (c >= 1) return 255;
    return static_cast<std::uint8_t>(std::lround(255 * c));
}

void write_ppm(std::ostream& out, const Raster& raster) {
    out << encode_image(raster, ImageEncoding{});
}

namespace {

// Reads PPM header fields: whitespace-separated decimal numbers with # comments.
bool is_ppm_space(int c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

// Only a regular file is read: a FIFO or a device could block rt for ever or feed it without
// end, and its size, which bounds what a header may claim, is unknown.
void require_regular(const struct stat& st) {
    if (S_ISDIR(st.st_mode)) throw Error("it is a directory");
    if (S_ISREG(st.st_mode)) return;
    const char* kind = S_ISFIFO(st.st_mode)   ? "a FIFO"
                       : S_ISCHR(st.st_mode)  ? "a character device"
                       : S_ISBLK(st.st_mode)  ? "a block device"
                       : S_ISSOCK(st.st_mode) ? "a socket"
                                              : "not a file";
    throw Error(std::string("it is not a regular file (") + kind + ")");
}

class PpmHeader {
  public:
    explicit PpmHeader(std::istream& in) : in_(in) {}

    long number(const char* what) {
        int c = in_.get();
        for (;;) {
            if (c == '#') {
                while (c != EOF && c != '\n') c = in_.get();
            } else if (is_ppm_space(c)) {
                c = in_.get();
            } else {
                break;
            }
        }
        if (c < '0' || c > '9') throw Error(std::string("expected ") + what + " in the PPM file");
        long value = 0;
        while (c >= '0' && c <= '9') {
            value = value * 10 + (c - '0');
            if (value > 1'000'000'000)
                throw Error(std::string(what) + " too large in the PPM file");
            c = in_.get();
        }
        last_ = c;  // the single whitespace character that ends the field
        return value;
    }
    int last() const { return last_; }

  private:
    std::istream& in_;
    int last_ = EOF;
};

}  // namespace

FileId texture_file(const std::filesystem::path& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        throw Error(std::string("cannot open it: ") + std::strerror(errno));
    require_regular(st);
    return {static_cast<std::uint64_t>(st.st_dev), static_cast<std::uint64_t>(st.st_ino)};
}

Image read_ppm(const std::filesystem::path& path) {
    texture_file(path);
    // Checked again on the open file, which may have been replaced since; O_NONBLOCK keeps a
    // FIFO put there meanwhile from blocking the open.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) throw Error(std::string("cannot open it: ") + std::strerror(errno));
    FdBuf buffer(fd, "cannot read it", true);
    struct stat st {};
    if (::fstat(fd, &st) != 0) throw Error(std::string("cannot read it: ") + std::strerror(errno));
    require_regular(st);
    std::istream in(&buffer);
    in.exceptions(std::ios::badbit);  // a read error is thrown, not taken for the end
    char magic[2] = {};
    in.read(magic, 2);
    if (!in || magic[0] != 'P' || (magic[1] != '6' && magic[1] != '3'))
        throw Error("not a PPM file (expected P6 or P3)");
    const bool binary = magic[1] == '6';
    if (!is_ppm_space(in.peek())) throw Error("not a PPM file (expected P6 or P3)");
    PpmHeader header(in);
    Image image;
    const long width = header.number("width");
    const long height = header.number("height");
    const long maxval = header.number("maximum value");
    if (width < 1 || height < 1) throw Error("PPM image has no pixels");
    // Each is at most 10^9, so the product cannot overflow a 64-bit long.
    if (width * height > kMaxImagePixels)
        throw Error("PPM image " + std::to_string(width) + "x" + std::to_string(height) +
                    " is larger than " + std::to_string(kMaxImagePixels) + " pixels");
    if (maxval < 1 || maxval > 65535) throw Error("PPM maximum value must be 1 to 65535");
    // The binary samples start after exactly one whitespace character.
    if (binary && !is_ppm_space(header.last()))
        throw Error("expected one whitespace character after the PPM maximum value");
    image.width = static_cast<int>(width);
    image.height = static_cast<int>(height);
    const std::size_t count = static_cast<std::size_t>(width * height) * 3;
    // A header can claim far more pixels than the file holds: check against the file's size
    // before allocating, so a short file costs nothing. Each binary sample takes one or two
    // bytes; each text sample at least one (digits and separators take more).
    const std::size_t bytes_per_sample = binary && maxval > 255 ? 2 : 1;
    const auto size = static_cast<std::int64_t>(st.st_size);
    const auto remaining =
        static_cast<std::size_t>(std::max<std::int64_t>(size - buffer.position(), 0));
    if (remaining < count * bytes_per_sample) throw Error("PPM pixel data ends early");
    image.values.resize(count);
    const double scale = 1.0 / static_cast<double>(maxval);
    for (std::size_t i = 0; i < count; ++i) {
        long value = 0;
        if (binary) {
            const int hi = in.get();
            const int lo = maxval > 255 ? in.get() : 0;
            if (hi == EOF || lo == EOF) throw Error("PPM pixel data ends early");
            value = maxval > 255 ? hi * 256 + lo : hi;
        } else {
            value = header.number("pixel value");
        }
        if (value > maxval) throw Error("PPM pixel value above the maximum value");
        image.values[i] = static_cast<float>(static_cast<double>(value) * scale);
    }
    return image;
}

}  // namespace rt
