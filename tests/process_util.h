// Runs the rt binary as a child process without a shell: for tests that need its pid (to
// signal it), another user (root only), or its standard output on a descriptor of their own.
#pragma once

#include <fcntl.h>
#include <grp.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "cli_util.h"

namespace rt_test {

inline bool running_as_root() { return ::geteuid() == 0; }

// The user tests switch to when run as root, to see what an ordinary user meets.
inline constexpr int kNobody = 65534;

struct SpawnOptions {
    int uid = -1;                  // switch to this user and group (root only); -1 keeps ours
    std::string stdout_path;       // relative to dir; "" is rt.out
    int stdout_fd = -1;            // or this descriptor, when >= 0
    int stdin_fd = -1;             // standard input from this descriptor, when >= 0
    int stderr_fd = -1;            // standard error to this descriptor instead of rt.err
    std::vector<std::string> env;  // extra NAME=VALUE settings
};

inline SpawnOptions as_user(int uid) {
    SpawnOptions options;
    options.uid = uid;
    return options;
}
inline SpawnOptions stdout_to(int fd) {
    SpawnOptions options;
    options.stdout_fd = fd;
    return options;
}

// Starts `rt args...` in `dir` with standard error in dir/rt.err; returns its pid.
inline pid_t spawn_rt(const std::filesystem::path& dir, const std::vector<std::string>& args,
                      const SpawnOptions& options = {}) {
    // Everything the child needs is prepared before fork(): after it, only plain calls.
    std::vector<std::string> words = {rt_binary()};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    const std::string dir_text = dir.string();
    const std::string out = options.stdout_path.empty() ? "rt.out" : options.stdout_path;
    std::vector<std::string> env_text = options.env;
    const pid_t pid = ::fork();
    if (pid != 0) return pid;
    if (::chdir(dir_text.c_str()) != 0) ::_exit(125);
    const int out_fd = options.stdout_fd >= 0
                           ? options.stdout_fd
                           : ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err_fd = ::open("rt.err", O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out_fd < 0 || err_fd < 0) ::_exit(125);
    ::dup2(out_fd, STDOUT_FILENO);
    ::dup2(options.stderr_fd >= 0 ? options.stderr_fd : err_fd, STDERR_FILENO);
    if (options.stdin_fd >= 0) ::dup2(options.stdin_fd, STDIN_FILENO);
    if (options.uid >= 0) {
        if (::fchown(err_fd, static_cast<uid_t>(options.uid), static_cast<gid_t>(options.uid)) !=
                0 ||
            ::setgroups(0, nullptr) != 0 || ::setgid(static_cast<gid_t>(options.uid)) != 0 ||
            ::setuid(static_cast<uid_t>(options.uid)) != 0)
            ::_exit(125);
    }
    for (std::string& e : env_text) ::putenv(e.data());
    ::execv(argv[0], argv.data());
    ::_exit(127);
}

// Waits for the child; kills it after `limit` so that a broken test cannot hang. Returns the
// raw wait status.
inline int wait_for(pid_t pid, std::chrono::seconds limit = std::chrono::seconds(120)) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    int status = 0;
    while (::waitpid(pid, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() > deadline) {
            ::kill(pid, SIGKILL);
            ::waitpid(pid, &status, 0);
            return status;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return status;
}

// Runs rt to the end: the exit status (or 128 + signal), and what it printed.
inline RunResult run_rt_args(const std::filesystem::path& dir, const std::vector<std::string>& args,
                             const SpawnOptions& options = {}) {
    const int status = wait_for(spawn_rt(dir, args, options));
    RunResult result;
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    if (options.stdout_fd < 0)
        result.out =
            read_file(dir / (options.stdout_path.empty() ? "rt.out" : options.stdout_path));
    result.err = read_file(dir / "rt.err");
    return result;
}

}  // namespace rt_test
