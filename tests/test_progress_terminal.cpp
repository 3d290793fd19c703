// The progress line on a terminal (a pseudo-terminal here): cut to the terminal's width so
// that it never wraps, and erased before "rt: interrupted" when Ctrl-C ends the render.
#include <fcntl.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <string>
#include <thread>

#include "batch/progress.h"
#include "check.h"
#include "cli_util.h"
#include "process_util.h"

using namespace rt_test;
namespace fs = std::filesystem;

namespace {

// A render of several seconds: a sphere light of 256 samples over 400 x 300 pixels.
const char* const kLongRender =
    "102  0 0 5  0 0 0  0.4 0 0  0 0.3 0  400 300\n103 0.1 0.1 0.1\n110 256 2 3 4 0.5 1 1 1\n"
    "1 1  0 0 0  100 0.8 0.3 0.2  0.3 20 0.6 0.2 1.5\n2 -1  0 1 0  100 0.6 0.6 0.6  0.5 10 0.5 0 "
    "1\n";

// Everything the master side has to read within `wait`.
std::string drain(int master, std::chrono::milliseconds wait) {
    std::string got;
    const auto until = std::chrono::steady_clock::now() + wait;
    while (std::chrono::steady_clock::now() < until) {
        pollfd p{master, POLLIN, 0};
        if (::poll(&p, 1, 50) <= 0) continue;
        char buffer[4096];
        const ssize_t n = ::read(master, buffer, sizeof buffer);
        if (n <= 0) break;
        got.append(buffer, static_cast<std::size_t>(n));
    }
    return got;
}

}  // namespace

TEST(the_line_is_cut_to_the_terminal_and_erased_before_the_interruption_message) {
    const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
    if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) return;  // no ptys
    const char* name = ::ptsname(master);
    const int slave = name != nullptr ? ::open(name, O_RDWR | O_NOCTTY) : -1;
    CHECK(slave >= 0);
    winsize size{};
    size.ws_col = 30;
    size.ws_row = 10;
    CHECK_EQ(::ioctl(slave, TIOCSWINSZ, &size), 0);
    const fs::path dir = work_dir("progress_terminal");
    write_file(dir / "slow.in", kLongRender);
    SpawnOptions options;
    options.stderr_fd = slave;
    const pid_t pid = spawn_rt(dir, {"-j", "1", "slow.in", "-o", "out.ppm"}, options);
    const std::string shown = drain(master, std::chrono::milliseconds(2000));
    ::kill(pid, SIGINT);
    const int status = wait_for(pid, std::chrono::seconds(60));
    const std::string rest = drain(master, std::chrono::milliseconds(300));
    CHECK(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT);
    // Each update: "\r", at most 29 columns of text, "\x1b[K".
    std::size_t updates = 0;
    for (std::size_t at = shown.find('\r'); at != std::string::npos;
         at = shown.find('\r', at + 1)) {
        const std::size_t end = shown.find("\x1b[K", at);
        if (end == std::string::npos) break;
        ++updates;
        CHECK(end - at - 1 <= 29);
    }
    CHECK(updates >= 2);
    CHECK_CONTAINS(shown.substr(0, 8), "\rrt: ");
    // The interruption message starts on a cleared line.
    CHECK_CONTAINS(shown + rest, "\r\x1b[Krt: interrupted\r\n");
    CHECK(!fs::exists(dir / "out.ppm"));
    ::close(slave);
    ::close(master);
}

TEST(lines_are_cut_only_where_a_width_is_known) {
    CHECK_EQ(rt::fit_to_width("rt:  45%  1.2 Mrays/s", 10), std::string("rt:  45% "));
    CHECK_EQ(rt::fit_to_width("rt:  45%", 9), std::string("rt:  45%"));
    CHECK_EQ(rt::fit_to_width("rt:  45%", 8), std::string("rt:  45"));
    CHECK_EQ(rt::fit_to_width("rt:  45%", 0), std::string("rt:  45%"));
}
