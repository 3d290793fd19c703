#include "common/fd_stream.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "common/digest.h"
#include "rt/error.h"

namespace rt {

FdBuf::FdBuf(int fd, std::string what, bool owns)
    : fd_(fd), what_(std::move(what)), owns_(owns), buffer_(new char[kSize]) {}

FdBuf::~FdBuf() {
    if (owns_) ::close(fd_);
}

FdBuf::int_type FdBuf::underflow() {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    // The end, once seen, stays: a terminal's Ctrl-D ends one read, and reading again would
    // wait for another.
    if (at_end_) return traits_type::eof();
    ssize_t got = 0;
    do {
        got = ::read(fd_, buffer_.get(), kSize);
    } while (got < 0 && errno == EINTR);
    if (got < 0) throw Error(what_ + ": " + std::strerror(errno));
    if (got == 0) {
        at_end_ = true;
        return traits_type::eof();
    }
    consumed_ += got;
    if (digest_ != nullptr) digest_->update({buffer_.get(), static_cast<std::size_t>(got)});
    setg(buffer_.get(), buffer_.get(), buffer_.get() + got);
    return traits_type::to_int_type(*gptr());
}

// Only the position can be asked (tellg); the buffer does not seek.
FdBuf::pos_type FdBuf::seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) {
    if (off != 0 || dir != std::ios_base::cur) return pos_type(off_type(-1));
    return pos_type(off_type(position()));
}

}  // namespace rt
