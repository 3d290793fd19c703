#include "scene/texture.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <string>

#include "common/fd_stream.h"
#include "common/message_text.h"
#include "rt/error.h"
#include "rt/image_file.h"

namespace rt {

namespace {

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

FileId texture_file(const std::filesystem::path& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        throw Error(std::string("cannot open it: ") + std::strerror(errno));
    require_regular(st);
    return {static_cast<std::uint64_t>(st.st_dev), static_cast<std::uint64_t>(st.st_ino)};
}

Image read_texture(const std::filesystem::path& path) {
    texture_file(path);
    // Checked again on the open file, which may have been replaced since; O_NONBLOCK keeps a
    // FIFO put there meanwhile from blocking the open.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) throw Error(std::string("cannot open it: ") + std::strerror(errno));
    FdBuf buffer(fd, "cannot read it", true);
    struct stat st {};
    if (::fstat(fd, &st) != 0) throw Error(std::string("cannot read it: ") + std::strerror(errno));
    require_regular(st);
    // The file is read whole, as far as the size it had when opened: the decoders check what a
    // header claims against the bytes there before allocating the pixels, so a short file
    // claiming a huge image costs nothing.
    std::string bytes(static_cast<std::size_t>(st.st_size), '\0');
    bytes.resize(static_cast<std::size_t>(
        buffer.sgetn(bytes.data(), static_cast<std::streamsize>(bytes.size()))));
    // PPM samples as the file has them, so that each is divided by the file's own maximum.
    ImageFile file = decode_image(bytes, PpmSamples::as_stored);
    std::string().swap(bytes);  // freed before the colours are made, to lower the peak
    return colours(std::move(file));
}

std::shared_ptr<const Image> TextureCache::load(const std::filesystem::path& resolved) {
    const FileId file = texture_file(resolved);
    // Every spelling is a dependency: a symbolic link among them can later be pointed at
    // another file.
    if (std::find(paths_.begin(), paths_.end(), resolved) == paths_.end())
        paths_.push_back(resolved);
    if (const auto known = images_.find(file); known != images_.end()) return known->second;
    auto image = std::make_shared<const Image>(read_texture(resolved));
    images_.emplace(file, image);
    return image;
}

}  // namespace rt
