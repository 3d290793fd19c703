// A client of GNU make's jobserver: under `make -jN`, rt takes the job tokens that are free
// at start-up (one more thread each) and gives every one back when it ends, however it ends.
#pragma once

#include <string>
#include <string_view>

namespace rt {

// What MAKEFLAGS says about the jobserver.
struct JobserverAuth {
    enum class Kind { none, pipe, fifo, disabled };
    Kind kind = Kind::none;
    int read_fd = -1;  // pipe: descriptors rt inherited from make
    int write_fd = -1;
    std::string fifo;      // fifo: the named pipe's path (make 4.4)
    bool dry_run = false;  // make -n, -q or -t: do nothing
};

// Reads --jobserver-auth=R,W, --jobserver-auth=fifo:PATH and the older --jobserver-fds=R,W
// (the last one counts), and the 'n' of make -n in MAKEFLAGS' first word. Negative
// descriptors mean make disabled the jobserver for this command.
JobserverAuth parse_makeflags(std::string_view makeflags);
// The same for this process's MAKEFLAGS (none when it is not set).
JobserverAuth jobserver_from_environment();

class JobserverClient {
  public:
    // Connects to the jobserver. Call it before rt opens any file: make closes the pipe's
    // descriptors for commands it does not think recursive, and a file opened later could
    // reuse their numbers. The client's own descriptors are close-on-exec.
    explicit JobserverClient(const JobserverAuth& auth);
    ~JobserverClient();  // gives the tokens back
    JobserverClient(const JobserverClient&) = delete;
    JobserverClient& operator=(const JobserverClient&) = delete;

    bool usable() const { return read_fd_ >= 0; }
    // Why a jobserver that MAKEFLAGS names cannot be used ("" when it can, or none is named).
    const std::string& problem() const { return problem_; }

    // Takes up to `wanted` tokens without waiting; returns how many it holds. The tokens are
    // registered with rt::interrupt, so a signal gives them back too.
    int acquire(int wanted);
    // Gives every held token back (the same bytes that were read, as make asks).
    void release();

  private:
    int read_fd_ = -1;   // a non-blocking descriptor of rt's own
    int write_fd_ = -1;  // make's (pipe) or rt's own (fifo)
    bool own_write_fd_ = false;
    std::string problem_;
};

}  // namespace rt
