// Interrupting the real rt while it checkpoints, for test_resume and test_kill_resume: a
// scene that reads a texture, and a way to stop rt once its checkpoint has reached a given
// size (every record then written slowly, in two halves, so that a stop can land inside one).
#pragma once

#include <sys/stat.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "batch/checkpoint.h"
#include "cli_util.h"
#include "process_util.h"

namespace rt_test {

// A sphere light over spheres and a floor, and an image-mapped picture (a texture the
// checkpoint's header must name): every row has a cost of its own, soft shadows included.
inline const char* const kResumeScene =
    "102  0 4.5 9  0 0.8 0  0.55 0 0  0 0.55 0  96 72\n"
    "103  0.06 0.06 0.06\n"
    "110  24  0.5 4.5 1  0.8  30 29 27\n"
    "2  0  0 1 0\n100  0.85 0.85 0.85  0 1  0.9  0 1\n"
    "1  1  0.2 1 -0.6\n100  0.9 0.25 0.2  0.2 40  0.7  0 1\n"
    "1  0.6  2.1 1.9 0.9\n100  0.2 0.4 0.9  0.6 40  0.3  0 1\n"
    "6  -3 0.3 -1.5  1.6 0 0  0 1.6 0\n"
    "108  -3 0.3 -1.5  1.6 0 0  0 1.6 0  letter-f.ppm\n  100  1 1 1  0 1 0.9 0 1\n";

// A directory holding the scene (scene.in) and its texture.
inline std::filesystem::path resume_dir(const std::string& name) {
    const std::filesystem::path dir = work_dir(name);
    write_file(dir / "scene.in", kResumeScene);
    std::filesystem::copy_file(
        std::filesystem::path(RT_SOURCE_DIR) / "scenes/textures/letter-f.ppm",
        dir / "letter-f.ppm");
    return dir;
}

inline std::uintmax_t size_of(const std::filesystem::path& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 ? static_cast<std::uintmax_t>(st.st_size) : 0;
}

// Runs `rt args...` in `dir` with its checkpoint at `checkpoint` written slowly, and sends it
// `sig` once the file holds at least `bytes`; returns rt's wait status (it may have finished
// first when `bytes` is more than the checkpoint ever holds).
inline int stop_at_size(const std::filesystem::path& dir, const std::vector<std::string>& args,
                        const std::filesystem::path& checkpoint, std::uintmax_t bytes,
                        int sig = SIGKILL) {
    SpawnOptions options;
    options.env = {"RT_DEBUG=checkpoint-slow"};
    const pid_t pid = spawn_rt(dir, args, options);
    int status = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (::waitpid(pid, &status, WNOHANG) == 0) {
        if (size_of(checkpoint) >= bytes || std::chrono::steady_clock::now() > deadline) {
            ::kill(pid, sig);
            return wait_for(pid);
        }
        std::this_thread::sleep_for(std::chrono::microseconds(300));
    }
    return status;
}

// What a checkpoint file holds now (its complete rows, and whether a damaged tail follows).
inline rt::CheckpointContents checkpoint_in(const std::filesystem::path& path) {
    return rt::read_checkpoint(read_file(path));
}

}  // namespace rt_test
