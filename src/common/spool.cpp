#include "common/spool.h"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "rt/error.h"

namespace rt {

namespace {

[[noreturn]] void fail(const char* what) {
    throw Error(std::string("cannot ") + what +
                " the temporary file holding the output: " + std::strerror(errno));
}

std::FILE* anonymous_file() {
    const char* dir = std::getenv("TMPDIR");
    std::string name =
        std::string(dir != nullptr && *dir != '\0' ? dir : "/tmp") + "/rt-spool.XXXXXX";
    const int fd = ::mkstemp(name.data());
    if (fd < 0) fail("create");
    ::unlink(name.c_str());  // gone once closed, even if the program is killed
    std::FILE* file = ::fdopen(fd, "w+b");
    if (file == nullptr) {
        ::close(fd);
        fail("open");
    }
    return file;
}

}  // namespace

Spool::Spool(std::size_t memory_limit) : memory_limit_(memory_limit) {
    setp(buffer_, buffer_ + sizeof buffer_);
}

Spool::~Spool() {
    if (file_ != nullptr) std::fclose(file_);
}

void Spool::spill(std::string_view bytes) {
    if (file_ == nullptr) {
        file_ = anonymous_file();
        spill(std::string_view(memory_));
        std::string().swap(memory_);
    }
    if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) fail("write");
}

void Spool::drain() {
    const std::string_view pending(pbase(), static_cast<std::size_t>(pptr() - pbase()));
    if (file_ == nullptr && memory_.size() + pending.size() <= memory_limit_)
        memory_.append(pending);
    else
        spill(pending);
    setp(buffer_, buffer_ + sizeof buffer_);
}

Spool::int_type Spool::overflow(int_type c) {
    drain();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
        *pptr() = traits_type::to_char_type(c);
        pbump(1);
    }
    return traits_type::not_eof(c);
}

int Spool::sync() {
    drain();
    return 0;
}

void Spool::each_piece(const std::function<void(std::string_view)>& sink) {
    drain();
    if (file_ == nullptr) {
        for (std::size_t at = 0; at < memory_.size(); at += std::size_t{1} << 20)
            sink(std::string_view(memory_).substr(at, std::size_t{1} << 20));
        return;
    }
    if (std::fflush(file_) != 0) fail("write");
    std::rewind(file_);
    std::vector<char> piece(std::size_t{1} << 20);
    for (;;) {
        const std::size_t n = std::fread(piece.data(), 1, piece.size(), file_);
        if (n > 0) sink(std::string_view(piece.data(), n));
        if (n < piece.size()) {
            if (std::ferror(file_)) fail("read back");
            return;
        }
    }
}

}  // namespace rt
