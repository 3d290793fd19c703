// The progress display: a line on stderr that shows how far a render has got, updated from a
// thread of its own while the render runs.
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <ostream>
#include <string>
#include <thread>

#include "rt/render.h"

namespace rt {

// "0:07", "1:05:09": whole seconds, as a clock shows them.
std::string format_duration(double seconds);
// "42%  12.3 Mrays/s  0:05 elapsed  0:07 left"; the time left is left out until it can be
// estimated (fraction 0). Of `fraction`, `resumed` was done before this run (rows from a
// checkpoint, which took no time): the time left is estimated from the rest.
std::string format_progress(double fraction, double rays_per_second, double elapsed_seconds,
                            double resumed = 0);
// The line cut to fit a terminal `columns` wide without wrapping (one column is left free, as
// a terminal wraps when the last one is written); 0 columns (unknown) leaves it whole.
std::string fit_to_width(std::string line, int columns);

class ProgressDisplay {
  public:
    enum class Style {
        terminal,  // one line, rewritten in place and erased at the end
        lines,     // a plain line now and then, and one at the end (for logs)
    };

    // Starts showing `progress` on `out` until destroyed (or finish() is called). In the
    // lines style each line names `label` (the image being made), so that lines from several
    // renders in one log can be told apart: "rt: out.png:  45% ...".
    ProgressDisplay(const RenderProgress& progress, Style style, std::ostream& out,
                    std::string label = {});
    ~ProgressDisplay() { finish(); }
    ProgressDisplay(const ProgressDisplay&) = delete;
    ProgressDisplay& operator=(const ProgressDisplay&) = delete;

    // Stops the display: the terminal line is erased, the lines style prints its last line.
    void finish();

  private:
    void run(std::stop_token stop);
    std::string current_line() const;
    std::string labelled(const std::string& line) const;

    const RenderProgress& progress_;
    Style style_;
    std::ostream& out_;
    std::string label_;
    std::chrono::steady_clock::time_point start_;
    std::mutex mutex_;
    std::condition_variable_any wake_;
    bool shown_ = false;   // whether the terminal line is on the screen
    std::jthread thread_;  // last: it starts once everything above is ready
};

}  // namespace rt
