#include "batch/progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/interrupt.h"

namespace rt {

namespace {

// A render shorter than this shows no terminal line at all, so quick renders do not flicker.
constexpr std::chrono::milliseconds kTerminalDelay{500};
constexpr std::chrono::milliseconds kTerminalInterval{250};
// Logs get a line this often: often enough to show life, rarely enough to stay readable.
constexpr std::chrono::seconds kLinesInterval{5};

}  // namespace

std::string format_duration(double seconds) {
    const long total = std::lround(std::max(0.0, seconds));
    char text[32];
    if (total >= 3600)
        std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", total / 3600, total / 60 % 60,
                      total % 60);
    else
        std::snprintf(text, sizeof text, "%ld:%02ld", total / 60, total % 60);
    return text;
}

std::string format_progress(double fraction, double rays_per_second, double elapsed_seconds,
                            double resumed) {
    char head[64];
    std::snprintf(head, sizeof head, "%3.0f%%  %.1f Mrays/s  ",
                  std::floor(100 * std::clamp(fraction, 0.0, 1.0)), rays_per_second / 1e6);
    std::string line = head + format_duration(elapsed_seconds) + " elapsed";
    if (fraction > resumed && fraction < 1)
        line += "  " + format_duration(elapsed_seconds * (1 - fraction) / (fraction - resumed)) +
                " left";
    return line;
}

std::string fit_to_width(std::string line, int columns) {
    if (columns > 1 && line.size() >= static_cast<std::size_t>(columns))
        line.resize(static_cast<std::size_t>(columns - 1));
    return line;
}

namespace {
// The width of the terminal on standard error, asked at every update so that a resized
// window is followed; 0 when it cannot be told.
int terminal_columns() {
    winsize size{};
    if (::ioctl(STDERR_FILENO, TIOCGWINSZ, &size) != 0) return 0;
    return size.ws_col;
}
}  // namespace

ProgressDisplay::ProgressDisplay(const RenderProgress& progress, Style style, std::ostream& out,
                                 std::string label)
    : progress_(progress),
      style_(style),
      out_(out),
      label_(std::move(label)),
      start_(std::chrono::steady_clock::now()),
      thread_([this](std::stop_token stop) { run(stop); }) {}

// "rt: out.png:  45% ..." for "rt:  45% ...".
std::string ProgressDisplay::labelled(const std::string& line) const {
    if (label_.empty()) return line;
    return "rt: " + label_ + ":" + line.substr(3);
}

std::string ProgressDisplay::current_line() const {
    const std::uint64_t total = progress_.rows_total.load(std::memory_order_relaxed);
    const std::uint64_t done = progress_.rows_done.load(std::memory_order_relaxed);
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const std::uint64_t restored = progress_.rows_restored.load(std::memory_order_relaxed);
    const auto share = [&](std::uint64_t rows) {
        return total > 0 ? static_cast<double>(rows) / static_cast<double>(total) : 0.0;
    };
    const double rate =
        elapsed > 0 ? static_cast<double>(progress_.rays.load(std::memory_order_relaxed)) / elapsed
                    : 0;
    return "rt: " + format_progress(share(done), rate, elapsed, share(restored));
}

void ProgressDisplay::run(std::stop_token stop) {
    std::unique_lock lock(mutex_);
    // Waits for the interval; true when the display is being stopped instead.
    const auto stopped_during = [&](auto interval) {
        wake_.wait_for(lock, stop, interval, [] { return false; });
        return stop.stop_requested();
    };
    if (style_ == Style::terminal) {
        // The interruption handler waits for a line being written, so it must not run here.
        const interrupt::SignalsBlocked blocked;
        if (stopped_during(kTerminalDelay)) return;
        do {
            // Back to the start of the line, the new text cut to the terminal's width (a line
            // that wraps cannot be rewritten in place), and the rest of the line cleared; one
            // write, so that nothing can come between its parts.
            const std::string line =
                '\r' + fit_to_width(current_line(), terminal_columns()) + "\x1b[K";
            if (!interrupt::begin_terminal_line()) return;
            out_ << line << std::flush;
            shown_ = true;
            interrupt::end_terminal_line(true);
        } while (!stopped_during(kTerminalInterval));
        return;
    }
    while (!stopped_during(kLinesInterval)) out_ << labelled(current_line()) << '\n' << std::flush;
}

void ProgressDisplay::finish() {
    if (!thread_.joinable()) return;
    thread_.request_stop();
    thread_.join();
    if (style_ == Style::terminal) {
        const interrupt::SignalsBlocked blocked;
        if (interrupt::begin_terminal_line()) {
            if (shown_) out_ << "\r\x1b[K" << std::flush;
            interrupt::end_terminal_line(false);
        }
    } else {
        out_ << labelled(current_line()) << '\n' << std::flush;
    }
}

}  // namespace rt
