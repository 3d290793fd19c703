#include "batch/jobserver.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "common/interrupt.h"

namespace rt {

namespace {

// MAKEFLAGS' words: separated by blanks, a backslash escaping the next character. Variable
// definitions come after a "--" word and are not flags.
std::vector<std::string> makeflags_words(std::string_view flags) {
    std::vector<std::string> words(1);
    for (std::size_t i = 0; i < flags.size(); ++i) {
        const char c = flags[i];
        if (c == '\\' && i + 1 < flags.size()) {
            words.back() += flags[++i];
        } else if (c == ' ' || c == '\t') {
            if (!words.back().empty()) words.emplace_back();
        } else {
            words.back() += c;
        }
    }
    if (words.back().empty()) words.pop_back();
    return words;
}

bool parse_fd_pair(std::string_view text, int& r, int& w) {
    const char* end = text.data() + text.size();
    const auto [comma, e1] = std::from_chars(text.data(), end, r);
    if (e1 != std::errc() || comma == end || *comma != ',') return false;
    const auto [stop, e2] = std::from_chars(comma + 1, end, w);
    return e2 == std::errc() && stop == end;
}

// A descriptor make passed on: open, a FIFO (a pipe), and open for `access`.
bool is_pipe_end(int fd, int access, struct stat& st) {
    const int flags = ::fcntl(fd, F_GETFL);
    if (flags < 0 || ::fstat(fd, &st) != 0 || !S_ISFIFO(st.st_mode)) return false;
    return (flags & O_ACCMODE) == access || (flags & O_ACCMODE) == O_RDWR;
}

}  // namespace

JobserverAuth jobserver_from_environment() {
    const char* makeflags = std::getenv("MAKEFLAGS");
    return parse_makeflags(makeflags != nullptr ? makeflags : "");
}

JobserverAuth parse_makeflags(std::string_view makeflags) {
    JobserverAuth auth;
    const std::vector<std::string> words = makeflags_words(makeflags);
    // The first word holds the one-letter flags without a dash ("ns"), when there are any.
    // make -n (print), -q (question) and -t (touch) run '+' lines too, but mean that nothing
    // is to be made.
    if (!words.empty() && words[0][0] != '-' && words[0].find('=') == std::string::npos)
        auth.dry_run = words[0].find_first_of("nqt") != std::string::npos;
    for (const std::string& word : words) {
        if (word == "--") break;
        std::string_view value;
        for (const std::string_view option : {"--jobserver-auth=", "--jobserver-fds="})
            if (word.rfind(option, 0) == 0) value = std::string_view(word).substr(option.size());
        if (value.empty()) continue;
        JobserverAuth found;
        found.dry_run = auth.dry_run;
        if (value.rfind("fifo:", 0) == 0) {
            found.kind = JobserverAuth::Kind::fifo;
            found.fifo = std::string(value.substr(5));
        } else if (parse_fd_pair(value, found.read_fd, found.write_fd)) {
            found.kind = found.read_fd < 0 || found.write_fd < 0 ? JobserverAuth::Kind::disabled
                                                                 : JobserverAuth::Kind::pipe;
        } else {
            continue;  // a form rt does not know (Windows' semaphores): as if none
        }
        auth = found;
    }
    return auth;
}

JobserverClient::JobserverClient(const JobserverAuth& auth) {
    if (auth.kind == JobserverAuth::Kind::pipe) {
        struct stat r {
        }, w{};
        if (!is_pipe_end(auth.read_fd, O_RDONLY, r) || !is_pipe_end(auth.write_fd, O_WRONLY, w) ||
            r.st_ino != w.st_ino || r.st_dev != w.st_dev) {
            problem_ = "MAKEFLAGS names the jobserver descriptors " + std::to_string(auth.read_fd) +
                       "," + std::to_string(auth.write_fd) +
                       " but they are not open: make passes them only to recipe lines it "
                       "thinks recursive; mark rt's recipe line with '+'";
            return;
        }
        // A reading descriptor of rt's own, so that it may be non-blocking: the one make
        // shares must stay blocking for everyone else.
        const std::string path = "/proc/self/fd/" + std::to_string(auth.read_fd);
        read_fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
        if (read_fd_ < 0) {
            problem_ = "cannot open the jobserver pipe without blocking (" + path + ": " +
                       std::strerror(errno) + ")";
            return;
        }
        write_fd_ = auth.write_fd;
    } else if (auth.kind == JobserverAuth::Kind::fifo) {
        struct stat st {};
        if (::stat(auth.fifo.c_str(), &st) != 0 || !S_ISFIFO(st.st_mode)) {
            problem_ = "the jobserver FIFO " + auth.fifo + " that MAKEFLAGS names is missing";
            return;
        }
        read_fd_ = ::open(auth.fifo.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
        // The FIFO has a reader now (ours), so opening for writing cannot block.
        write_fd_ = ::open(auth.fifo.c_str(), O_WRONLY | O_CLOEXEC);
        own_write_fd_ = true;
        if (read_fd_ < 0 || write_fd_ < 0) {
            problem_ = "cannot open the jobserver FIFO " + auth.fifo + ": " + std::strerror(errno);
            if (read_fd_ >= 0) ::close(read_fd_);
            read_fd_ = -1;
        }
    }
}

JobserverClient::~JobserverClient() {
    release();
    if (read_fd_ >= 0) ::close(read_fd_);
    if (own_write_fd_ && write_fd_ >= 0) ::close(write_fd_);
}

int JobserverClient::acquire(int wanted) {
    if (!usable()) return 0;
    release();
    if (wanted > interrupt::kMaxTokens) wanted = interrupt::kMaxTokens;
    std::vector<char> tokens(static_cast<std::size_t>(wanted > 0 ? wanted : 0));
    // Held by rt::interrupt before a signal can end rt, so none is lost.
    const interrupt::SignalsBlocked blocked;
    int taken = 0;
    while (taken < wanted) {
        const ssize_t n = ::read(read_fd_, tokens.data() + taken, 1);
        if (n < 0 && errno == EINTR) continue;
        if (n != 1) break;  // EAGAIN: no token free now
        ++taken;
    }
    interrupt::hold_tokens(write_fd_, tokens.data(), taken);
    return taken;
}

void JobserverClient::release() { interrupt::give_back_tokens(); }

}  // namespace rt
