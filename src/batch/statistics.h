// What --stats prints at the end of a render: where the time went, what was traced, and what
// it cost.
#pragma once

#include <cstdint>
#include <string>

#include "rt/reader.h"  // StageTimes
#include "rt/trace.h"

namespace rt {

struct RunStatistics {
    StageTimes times;
    RenderStats rays;
    int threads = 0;
    std::size_t objects = 0;
    std::size_t lights = 0;
    std::uint64_t peak_memory_bytes = 0;
    // --checkpoint: the rows (of both passes under -a) and how many came from the file.
    bool checkpoint = false;
    std::uint64_t rows = 0;
    std::uint64_t rows_resumed = 0;
};

// The process's peak resident memory so far, in bytes (0 where the system does not say).
std::uint64_t peak_memory_bytes();

// The lines --stats prints, each starting "rt: stats: " and ending in a newline.
std::string format_statistics(const RunStatistics& s);

}  // namespace rt
