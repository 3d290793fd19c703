#include "common/interrupt.h"

#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

namespace rt::interrupt {

namespace {

// Lock-free atomics are the only shared state a signal handler may touch safely.
static_assert(std::atomic<int>::is_always_lock_free);

constexpr int kSlots = 4;  // the image, the -M file, and room to spare
enum SlotState : int { kFree, kFilling, kArmed };

// Fixed buffers: the handler cannot allocate.
char g_paths[kSlots][PATH_MAX];
std::atomic<int> g_slot_state[kSlots];

char g_tokens[kMaxTokens];
std::atomic<int> g_token_count{0};
std::atomic<int> g_token_fd{-1};

std::atomic<int> g_handling{0};  // 1 while a handler cleans up, 2 once it is done

constexpr int kHandled[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE};

// "PROGRAM: interrupted\n", set before the handler is installed.
char g_interrupted[64] = "rt: interrupted\n";
// Whether a progress line is on the terminal, and whether it is being written
// (interrupt::begin_terminal_line).
std::atomic<bool> g_terminal_line{false};
std::atomic<bool> g_terminal_writing{false};
static_assert(std::atomic<bool>::is_always_lock_free, "read in a signal handler");

// The checkpoint file, and whether a record is being written to it.
std::atomic<int> g_checkpoint_fd{-1};
std::atomic<bool> g_checkpoint_writing{false};

// Waits, for at most about a second (a terminal stopped by Ctrl-S, a stalled disk must not
// hang the exit), for a write in another thread to end.
void wait_for_writer(const std::atomic<bool>& writing) {
    for (int i = 0; i < 1000 && writing.load(); ++i) {
        timespec pause{0, 1'000'000};
        ::nanosleep(&pause, nullptr);
    }
}

void write_stderr(const char* text) {
    std::size_t left = std::strlen(text);
    while (left > 0) {
        const ssize_t n = ::write(STDERR_FILENO, text, left);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return;
        text += n;
        left -= static_cast<std::size_t>(n);
    }
}

extern "C" void on_signal(int sig) {
    const int saved_errno = errno;
    int expected = 0;
    if (g_handling.compare_exchange_strong(expected, 1)) {
        for (int i = 0; i < kSlots; ++i)
            if (g_slot_state[i].exchange(kFree) == kArmed) ::unlink(g_paths[i]);
        give_back_tokens();
        if (const int fd = g_checkpoint_fd.load(); fd >= 0) {
            wait_for_writer(g_checkpoint_writing);
            ::fdatasync(fd);
        }
        // A reader that went away (SIGPIPE) is not news to the user.
        if (sig != SIGPIPE) {
            wait_for_writer(g_terminal_writing);
            if (g_terminal_line.load()) write_stderr("\r\x1b[K");
            write_stderr(g_interrupted);
        }
        g_handling.store(2);
    } else {
        // Another thread is cleaning up: let it finish before this signal ends the process.
        while (g_handling.load() != 2) {
        }
    }
    // End as killed by the signal: the default action runs once this handler returns (the
    // signal is blocked until then).
    struct sigaction dfl {};
    dfl.sa_handler = SIG_DFL;
    sigemptyset(&dfl.sa_mask);
    sigaction(sig, &dfl, nullptr);
    raise(sig);
    errno = saved_errno;
}

sigset_t handled_set() {
    sigset_t set;
    sigemptyset(&set);
    for (const int sig : kHandled) sigaddset(&set, sig);
    return set;
}

// Sequentially consistent on both sides: the writer stores "writing" then reads "handling",
// the handler stores "handling" then reads "writing", so at least one of them sees the other.
bool begin_guarded_write(std::atomic<bool>& writing) {
    writing.store(true);
    if (g_handling.load() == 0) return true;
    writing.store(false);
    return false;
}

}  // namespace

bool begin_terminal_line() { return begin_guarded_write(g_terminal_writing); }

void end_terminal_line(bool shown) {
    g_terminal_line.store(shown);
    g_terminal_writing.store(false);
}

void set_checkpoint(int fd) { g_checkpoint_fd.store(fd); }
bool begin_checkpoint_write() { return begin_guarded_write(g_checkpoint_writing); }
void end_checkpoint_write() { g_checkpoint_writing.store(false); }

void install_handlers(std::string_view program) {
    const std::string_view tail = ": interrupted\n";
    if (program.size() + tail.size() < sizeof g_interrupted) {
        std::memcpy(g_interrupted, program.data(), program.size());
        std::memcpy(g_interrupted + program.size(), tail.data(), tail.size());
        g_interrupted[program.size() + tail.size()] = '\0';
    }
    struct sigaction action {};
    action.sa_handler = on_signal;
    action.sa_mask = handled_set();  // one clean-up at a time in a thread
    action.sa_flags = SA_RESTART;
    for (const int sig : kHandled) {
        struct sigaction old {};
        if (sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
        sigaction(sig, &action, nullptr);
    }
}

int register_temporary(const std::string& path) {
    if (path.size() >= PATH_MAX) return -1;
    for (int i = 0; i < kSlots; ++i) {
        int expected = kFree;
        if (!g_slot_state[i].compare_exchange_strong(expected, kFilling)) continue;
        std::memcpy(g_paths[i], path.c_str(), path.size() + 1);
        g_slot_state[i].store(kArmed);
        return i;
    }
    return -1;
}

void forget_temporary(int slot) {
    if (slot >= 0 && slot < kSlots) g_slot_state[slot].store(kFree);
}

void hold_tokens(int fd, const char* tokens, int count) {
    give_back_tokens();  // never two sets at once
    if (count > kMaxTokens) count = kMaxTokens;
    std::memcpy(g_tokens, tokens, static_cast<std::size_t>(count));
    g_token_fd.store(fd);
    g_token_count.store(count);
}

int give_back_tokens() {
    // Whoever takes the count writes the tokens: the handler and a normal exit never both do.
    const int count = g_token_count.exchange(0);
    const int fd = g_token_fd.load();
    int written = 0;
    while (written < count) {
        const ssize_t n =
            ::write(fd, g_tokens + written, static_cast<std::size_t>(count - written));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        written += static_cast<int>(n);
    }
    return written;
}

int tokens_held() { return g_token_count.load(); }

SignalsBlocked::SignalsBlocked() {
    const sigset_t set = handled_set();
    pthread_sigmask(SIG_BLOCK, &set, &previous_);
}

SignalsBlocked::~SignalsBlocked() { pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }

}  // namespace rt::interrupt
