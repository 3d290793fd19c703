// How rt, rtpp and rtimg end: their exit statuses, the one wrapper that turns what their
// work throws into a message and a status, and writing their text to standard output.
#pragma once

#include <functional>
#include <string_view>

namespace rt {

inline constexpr int kExitOk = 0;
inline constexpr int kExitError = 1;  // a scene, image or input/output error
inline constexpr int kExitUsage = 2;  // the command line made no sense

// What a program's messages start with, and how it ends on an error.
struct ProgramErrors {
    std::string_view name;          // "rt": "rt: out of memory"
    int error_status = kExitError;  // rtimg diff ends 2 on any error, so that 1 means "differ"
    // rt::Error messages begin with their place (a file's name) and are printed as they are;
    // rtimg prints them after its name, as every other message.
    bool name_located_errors = false;
};

// Runs `work` and returns its status. What it throws becomes one message on standard error
// (made printable) and a status: a UsageError "NAME: MESSAGE" and a pointer to --help, status
// 2; an rt::Error its message; std::bad_alloc "NAME: out of memory"; any other std::exception
// "NAME: WHAT"; those three `program.error_status`.
int run_guarded(const ProgramErrors& program, const std::function<int()>& work);

// Writes text for standard output (--help, --version, rt -r, rtpp's scene) and flushes it;
// a full disk or a closed pipe is an error, not a silent success: "NAME: cannot write to
// standard output: REASON" and kExitError.
int print_to_stdout(std::string_view program, std::string_view text);

}  // namespace rt
