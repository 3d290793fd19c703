#include "batch/checkpoint_store.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <thread>

#include "common/interrupt.h"
#include "common/message_text.h"
#include "rt/error.h"

namespace rt {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Rows go to the file as they finish (so a killed render keeps them: the system has them);
// they are forced to the disk this often, or less often when forcing takes long, so that
// syncing never costs more than about a twentieth of one thread's time.
constexpr Clock::duration kSyncInterval = std::chrono::seconds(2);
constexpr int kSyncCostShare = 20;

// The bytes a row's record takes: "RTCK", type, length, pass, y, x0, count, values, CRC.
std::uint64_t row_record_bytes(int width) {
    return 4 + 1 + 4 + 13 + std::uint64_t{24} * static_cast<std::uint64_t>(width) + 4;
}

std::uint64_t row_count(const PixelRect& r) { return r.empty() ? 0 : r.height(); }

bool same_file(const struct stat& a, const struct stat& b) {
    return a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

// RT_DEBUG=checkpoint-slow: each record is written in two halves a few milliseconds apart,
// so that tests can kill rt in the middle of one.
bool slow_writes() {
    const char* debug = std::getenv("RT_DEBUG");
    return debug != nullptr && std::strstr(debug, "checkpoint-slow") != nullptr;
}

std::string located(const std::string& path, const std::string& message) {
    return show_token(path, kShowWhole) + ": " + message;
}

// One message, written at once: renders that share a terminal (make -j) must not interleave
// their words.
void say(const std::string& line) { std::cerr << line + "\n" << std::flush; }

}  // namespace

CheckpointStore::CheckpointStore(CheckpointPlan plan, RenderProgress* progress)
    : plan_(std::move(plan)),
      progress_(progress),
      last_sync_(Clock::now()),
      sync_interval_(kSyncInterval) {
    const std::string& path = plan_.path;
    struct stat st {};
    const bool exists = ::stat(path.c_str(), &st) == 0;
    if (exists && !S_ISREG(st.st_mode))
        throw Error(located(path, "a checkpoint must be a regular file"));
    // Never over what the render reads or writes; names that do not exist yet are compared
    // as paths.
    for (const std::string& output : plan_.outputs) {
        struct stat out {};
        std::error_code ec;
        if ((exists && ::stat(output.c_str(), &out) == 0 && same_file(st, out)) ||
            fs::weakly_canonical(path, ec) == fs::weakly_canonical(output, ec))
            throw Error(located(path, "is also an output of this render (" +
                                          quote_token(output, kShowWhole) +
                                          "): give the checkpoint a name of its own"));
    }
    if (exists)
        for (const InputFile& input : plan_.inputs) {
            struct stat in {};
            if (!input.path.empty() && ::stat(input.path.c_str(), &in) == 0 && same_file(st, in))
                throw Error(located(path, "is " + input.role + " " +
                                              quote_token(input.path.string(), kShowWhole) +
                                              ", which this render reads: a checkpoint must be "
                                              "a file of its own"));
        }
    if (exists && !plan_.resume) {
        // Only a checkpoint's own name: another file there is refused either way.
        throw Error(located(path,
                            "is already there: add --resume to continue from it, or "
                            "remove it to render from the start"));
    }
    if (!exists && plan_.resume && !plan_.quiet)
        say("rt: note: no checkpoint " + quote_token(path, kShowWhole) +
            " to resume from: rendering from the start");
    if (!exists || !resume_from_file()) create();
    interrupt::set_checkpoint(fd_);
}

CheckpointStore::~CheckpointStore() {
    interrupt::set_checkpoint(-1);
    if (fd_ >= 0) ::close(fd_);
}

// A new checkpoint: the header is written whole and put in place at once (as an image is),
// so the file is either absent or starts with a complete header.
void CheckpointStore::create() {
    OutputFile file(plan_.path, plan_.inputs, "the checkpoint");
    file.write_bytes(encode_checkpoint_start(plan_.header));
    fd_ = ::open(plan_.path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
    if (fd_ < 0 || ::fdatasync(fd_) != 0)
        throw Error(located(plan_.path,
                            std::string("cannot write the checkpoint: ") + std::strerror(errno)));
}

// Reads the checkpoint there; false when its header is damaged, so nothing in it can be
// trusted and it is started again.
bool CheckpointStore::resume_from_file() {
    const std::string& path = plan_.path;
    fd_ = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
    if (fd_ < 0)
        throw Error(
            located(path, std::string("cannot open the checkpoint: ") + std::strerror(errno)));
    // No more than a complete checkpoint of this render can hold is read: what follows is a
    // damaged tail, whatever the file's size.
    const std::uint64_t limit =
        encode_checkpoint_start(plan_.header).size() + kMaxCheckpointHeader +
        row_count(plan_.rows) * row_record_bytes(plan_.rows.width()) +
        row_count(plan_.one_ray_rows) * row_record_bytes(plan_.one_ray_rows.width());
    std::string bytes;
    char buffer[1 << 16];
    while (bytes.size() < limit) {
        const ssize_t n = ::read(fd_, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0)
            throw Error(
                located(path, std::string("cannot read the checkpoint: ") + std::strerror(errno)));
        if (n == 0) break;
        bytes.append(buffer, static_cast<std::size_t>(n));
    }
    struct stat st {};
    const bool longer = ::fstat(fd_, &st) == 0 && static_cast<std::uint64_t>(st.st_size) > limit;
    if (bytes.size() > limit) bytes.resize(limit);
    CheckpointContents contents;
    try {
        contents = read_checkpoint(bytes);
    } catch (const CheckpointHeaderDamaged& e) {
        if (!plan_.quiet)
            say("rt: warning: " + located(path, e.what()) +
                ", so nothing in it can be used: rendering from the start");
        ::close(fd_);
        fd_ = -1;
        return false;
    } catch (const Error& e) {
        throw Error(located(path, std::string(e.what()) +
                                      "; rt writes a checkpoint only over its own: choose "
                                      "another name"));
    }
    if (const std::string differs = checkpoint_differences(plan_.header, contents.header);
        !differs.empty())
        throw Error(located(path, "the checkpoint was made by another render (" + differs +
                                      "): remove it to render from the start, or give the "
                                      "command it was made by"));
    // Rows that fit this render's rows and columns, the first of each.
    for (CheckpointRow& row : contents.rows) {
        const PixelRect& rect = row.pass == 0 ? plan_.one_ray_rows : plan_.rows;
        const bool fits =
            !rect.empty() && static_cast<int>(row.y) >= rect.y0 &&
            static_cast<int>(row.y) < rect.y1 && static_cast<int>(row.x0) == rect.x0 &&
            row.values.size() == static_cast<std::size_t>(rect.width()) * kSpectrumComponents;
        if (fits) held_.try_emplace({row.pass, static_cast<int>(row.y)}, std::move(row));
    }
    if (contents.damaged || longer) {
        if (::ftruncate(fd_, static_cast<off_t>(contents.kept_bytes)) != 0)
            throw Error(located(path, std::string("cannot cut the damaged tail off the "
                                                  "checkpoint: ") +
                                          std::strerror(errno)));
        if (!plan_.quiet)
            say("rt: note: " +
                located(path, "cut off a damaged or incomplete tail of " +
                                  std::to_string(
                                      std::max<std::uint64_t>(
                                          static_cast<std::uint64_t>(st.st_size), bytes.size()) -
                                      contents.kept_bytes) +
                                  " bytes after the last complete row"));
    }
    if (::fcntl(fd_, F_SETFL, O_APPEND) != 0 || ::lseek(fd_, 0, SEEK_END) < 0)
        throw Error(
            located(path, std::string("cannot append to the checkpoint: ") + std::strerror(errno)));
    if (!plan_.quiet)
        say("rt: resuming from " + quote_token(path, kShowWhole) + ": " +
            std::to_string(held_.size()) + " of " +
            std::to_string(row_count(plan_.rows) + row_count(plan_.one_ray_rows)) + " rows done");
    return true;
}

bool CheckpointStore::restore(int pass, int y, int x0, int x1, double* values) {
    const auto it = held_.find({pass, y});
    if (it == held_.end()) return false;
    const CheckpointRow& row = it->second;
    if (static_cast<int>(row.x0) != x0 ||
        row.values.size() != static_cast<std::size_t>(x1 - x0) * kSpectrumComponents)
        return false;
    std::copy(row.values.begin(), row.values.end(), values);
    ++resumed_;
    if (progress_ != nullptr) progress_->rows_restored.fetch_add(1, std::memory_order_relaxed);
    return true;
}

void CheckpointStore::finished(int pass, int y, int x0, int x1, const double* values) {
    CheckpointRow row;
    row.pass = static_cast<std::uint8_t>(pass);
    row.y = static_cast<std::uint32_t>(y);
    row.x0 = static_cast<std::uint32_t>(x0);
    row.values.assign(values, values + static_cast<std::size_t>(x1 - x0) * kSpectrumComponents);
    const std::string record = encode_checkpoint_row(row);
    {
        const std::lock_guard lock(write_mutex_);
        if (broken_) return;
        // A signal's handler waits for this record, so it must run on another thread.
        const interrupt::SignalsBlocked blocked;
        if (!interrupt::begin_checkpoint_write()) return;  // rt is ending: the file is final
        append(record);
        interrupt::end_checkpoint_write();
    }
    sync_now_and_then();
}

// Writes one record; a failure (a full disk) ends checkpointing, never the render.
void CheckpointStore::append(const std::string& record) {
    static const bool slow = slow_writes();
    std::string_view left = record;
    while (!left.empty()) {
        std::size_t chunk = left.size();
        if (slow && left.size() == record.size()) chunk = record.size() / 2;
        const ssize_t n = ::write(fd_, left.data(), chunk);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            warn_once(n < 0 ? std::strerror(errno) : "nothing written");
            return;
        }
        left.remove_prefix(static_cast<std::size_t>(n));
        if (slow && !left.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(3));
    }
}

void CheckpointStore::sync_now_and_then() {
    bool expected = false;
    if (!syncing_.compare_exchange_strong(expected, true)) return;  // another thread syncs
    const auto start = Clock::now();
    if (start - last_sync_ >= sync_interval_) {
        if (::fdatasync(fd_) != 0) {
            const std::lock_guard lock(write_mutex_);
            warn_once(std::strerror(errno));
        }
        const auto took = Clock::now() - start;
        sync_interval_ = std::max(kSyncInterval, took * kSyncCostShare);
        last_sync_ = Clock::now();
    }
    syncing_.store(false);
}

// Called with write_mutex_ held.
void CheckpointStore::warn_once(const std::string& why) {
    if (broken_) return;
    broken_ = true;
    if (plan_.quiet) return;
    // A progress line on the terminal is rewritten in place: start on a clean line.
    say(std::string(isatty(STDERR_FILENO) != 0 ? "\r\x1b[K" : "") + "rt: warning: " +
        located(plan_.path, "cannot write the checkpoint (" + why +
                                "): the render goes on without checkpoints"));
}

void CheckpointStore::remove() {
    interrupt::set_checkpoint(-1);
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    if (::unlink(plan_.path.c_str()) != 0 && errno != ENOENT)
        say("rt: warning: " + located(plan_.path, std::string("cannot remove the checkpoint: ") +
                                                      std::strerror(errno)));
}

}  // namespace rt
