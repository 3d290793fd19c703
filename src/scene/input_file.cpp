#include "scene/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "common/fd_stream.h"
#include "rt/error.h"

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

}  // namespace

FileId regular_file_id(const std::filesystem::path& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        throw Error(std::string("cannot open it: ") + std::strerror(errno));
    require_regular(st);
    return {static_cast<std::uint64_t>(st.st_dev), static_cast<std::uint64_t>(st.st_ino)};
}

std::string read_regular_file(const std::filesystem::path& path) {
    regular_file_id(path);
    // Checked again on the open file, which may have been replaced since; O_NONBLOCK keeps a
    // FIFO put there meanwhile from blocking the open.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) throw Error(std::string("cannot open it: ") + std::strerror(errno));
    FdBuf buffer(fd, "cannot read it", true);
    struct stat st {};
    if (::fstat(fd, &st) != 0) throw Error(std::string("cannot read it: ") + std::strerror(errno));
    require_regular(st);
    // Read whole, as far as the size it had when opened: decoders check what a header claims
    // against the bytes there before allocating, so a short file claiming much costs nothing.
    std::string bytes(static_cast<std::size_t>(st.st_size), '\0');
    bytes.resize(static_cast<std::size_t>(
        buffer.sgetn(bytes.data(), static_cast<std::streamsize>(bytes.size()))));
    return bytes;
}

}  // namespace rt
