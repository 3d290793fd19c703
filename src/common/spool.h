// Text written once and read back once, of any length in bounded memory: held in memory up
// to a limit, then in an anonymous temporary file. rtpp spools a translation there, so that
// nothing is written unless it completes, whatever the size of the input.
#pragma once

#include <cstddef>
#include <cstdio>
#include <functional>
#include <streambuf>
#include <string>
#include <string_view>

namespace rt {

class Spool : public std::streambuf {
  public:
    // Up to `memory_limit` bytes are kept in memory; the rest go to a temporary file in
    // $TMPDIR (or /tmp), removed from its directory as soon as it is made.
    explicit Spool(std::size_t memory_limit = std::size_t{8} << 20);
    ~Spool() override;
    Spool(const Spool&) = delete;
    Spool& operator=(const Spool&) = delete;

    // Passes everything written, in order, to `sink` in pieces of at most 1 MiB. Throws
    // rt::Error when the temporary file cannot be written or read back.
    void each_piece(const std::function<void(std::string_view)>& sink);
    // Whether the text outgrew memory (for tests).
    bool spilled() const { return file_ != nullptr; }

  protected:
    int_type overflow(int_type c) override;
    int sync() override;

  private:
    void drain();  // the put area into memory or the file
    void spill(std::string_view bytes);

    std::size_t memory_limit_;
    std::string memory_;
    std::FILE* file_ = nullptr;
    char buffer_[1 << 16];
};

}  // namespace rt
