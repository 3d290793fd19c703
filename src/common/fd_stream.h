// A stream buffer over a POSIX file descriptor that reports read errors instead of taking them
// for the end of the input, as std::filebuf does (a closed standard input or a directory would
// otherwise read as an empty scene).
#pragma once

#include <cstdint>
#include <memory>
#include <streambuf>
#include <string>

namespace rt {

class Sha256;  // common/digest.h

class FdBuf : public std::streambuf {
  public:
    // `what` names the input in the error a failed read throws: rt::Error("<what>: <reason>").
    // With `owns`, the descriptor is closed with the buffer.
    FdBuf(int fd, std::string what, bool owns);
    ~FdBuf() override;
    FdBuf(const FdBuf&) = delete;
    FdBuf& operator=(const FdBuf&) = delete;

    // Bytes handed out so far.
    std::int64_t position() const { return consumed_ - (egptr() - gptr()); }
    // Every byte read from now on is also given to `digest` (none when null).
    void digest_into(Sha256* digest) { digest_ = digest; }

  protected:
    int_type underflow() override;
    pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override;

  private:
    static constexpr std::size_t kSize = 64 * 1024;
    int fd_;
    std::string what_;
    bool owns_;
    std::unique_ptr<char[]> buffer_;
    std::int64_t consumed_ = 0;  // bytes read from the descriptor
    bool at_end_ = false;        // read() has returned 0
    Sha256* digest_ = nullptr;
};

}  // namespace rt
