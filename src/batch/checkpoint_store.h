// rt's --checkpoint file while a render runs: the rows a resumed render takes instead of
// tracing them, and the rows it finishes, appended as they come (the format is in
// batch/checkpoint.h; docs/cli.md, CHECKPOINTS, says what a user sees).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "batch/checkpoint.h"
#include "common/output_file.h"  // InputFile
#include "rt/render.h"

namespace rt {

// The files a checkpoint must never be written over, and what else the store needs to know.
struct CheckpointPlan {
    std::string path;
    CheckpointHeader header;           // what identifies the render (render_identity + digests)
    bool resume = false;               // --resume: continue from the file when it is there
    bool quiet = false;                // -q: no notes
    std::vector<InputFile> inputs;     // the scene (empty path for stdin), textures, mesh files
    std::vector<std::string> outputs;  // the image (not "-") and the -M rule
    PixelRect rows;                    // the rows and columns of the final pass (the region)
    PixelRect one_ray_rows;  // those of -a's one-ray pass (region and margin); empty without -a
};

class CheckpointStore final : public RowStore {
  public:
    // Claims the file before rendering: creates it with its header, or with --resume reads
    // what it holds and keeps every complete record (a damaged tail is cut off). Throws
    // rt::Error when the file may not be used: one of the render's inputs or outputs, not a
    // regular file, not an rt checkpoint, present without --resume, or made by another
    // render (the message says what differs).
    CheckpointStore(CheckpointPlan plan, RenderProgress* progress);
    ~CheckpointStore() override;
    CheckpointStore(const CheckpointStore&) = delete;
    CheckpointStore& operator=(const CheckpointStore&) = delete;

    bool restore(int pass, int y, int x0, int x1, double* values) override;
    void finished(int pass, int y, int x0, int x1, const double* values) override;

    // The image is written: the checkpoint has done its work and is removed.
    void remove();

    std::uint64_t rows_resumed() const { return resumed_.load(); }

  private:
    void create();
    bool resume_from_file();
    void append(const std::string& record);
    void sync_now_and_then();
    void warn_once(const std::string& why);

    CheckpointPlan plan_;
    RenderProgress* progress_;
    int fd_ = -1;
    // The rows read back, by pass and row.
    std::map<std::pair<int, int>, CheckpointRow> held_;
    std::atomic<std::uint64_t> resumed_{0};

    std::mutex write_mutex_;  // one record at a time goes to the file
    bool broken_ = false;     // a write failed: the render goes on without checkpoints
    std::atomic<bool> syncing_{false};
    std::chrono::steady_clock::time_point last_sync_;
    std::chrono::steady_clock::duration sync_interval_;
};

}  // namespace rt
