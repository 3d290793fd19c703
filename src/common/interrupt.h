// What rt must undo when SIGINT, SIGTERM or SIGHUP ends it early: temporary files to remove
// and GNU make jobserver tokens to give back. The signal handler reads only what is
// registered here, with async-signal-safe calls, then re-raises the signal so that rt ends
// as killed by it (make and shells see that and stop).
#pragma once

#include <csignal>
#include <string>
#include <string_view>

namespace rt::interrupt {

// Installs the handler for SIGINT, SIGTERM and SIGHUP (which print "PROGRAM: interrupted",
// "rt: interrupted" by default) and SIGPIPE (silent), leaving alone any of them that the
// parent set to be ignored (nohup).
void install_handlers(std::string_view program = "rt");

// Registers a file for the handler to unlink; returns a slot for forget_temporary(), or -1
// when the path is too long to hold or every slot is taken (nothing is registered then).
int register_temporary(const std::string& path);
// The file was renamed or removed: the handler must leave that name alone.
void forget_temporary(int slot);

// The progress line on the terminal that standard error is. The handler erases it before its
// message, so that "rt: interrupted" starts a clean line, and the two never interleave: the
// writer calls begin_terminal_line() first, which says false once a handler has taken the
// terminal (write nothing then), and end_terminal_line(shown) when its write is complete, a
// line now shown or not. The handler waits for a write in progress to end, so the writing
// thread must block the handled signals (SignalsBlocked) while it writes.
bool begin_terminal_line();
void end_terminal_line(bool shown);

// The checkpoint being written (--checkpoint), or -1 for none: the handler waits for a record
// being written to end (the writing thread must block the handled signals meanwhile), lets
// no other begin (begin_checkpoint_write() says false then: write nothing) and flushes the
// file to disk (fdatasync) before rt ends, so that it ends with the last row finished,
// complete. The file itself stays: it is what a resumed render continues from.
void set_checkpoint(int fd);
bool begin_checkpoint_write();
void end_checkpoint_write();

// Jobserver tokens taken: the handler, or give_back_tokens(), writes them back to fd.
inline constexpr int kMaxTokens = 1024;
void hold_tokens(int fd, const char* tokens, int count);
// Writes every held token back once (async-signal-safe); returns how many it wrote.
int give_back_tokens();
int tokens_held();

// Blocks the handled signals in this thread while it lives, so that a token read or a file
// created is registered before a signal can end rt, and so that the progress thread never
// runs the handler that waits for its write (a signal then goes to another thread).
class SignalsBlocked {
  public:
    SignalsBlocked();
    ~SignalsBlocked();
    SignalsBlocked(const SignalsBlocked&) = delete;
    SignalsBlocked& operator=(const SignalsBlocked&) = delete;

  private:
    sigset_t previous_;
};

}  // namespace rt::interrupt
