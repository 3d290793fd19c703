// Runs the rt binary through the shell and captures what it printed and its exit status.
#pragma once

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace rt_test {

// A small scene (8 x 6 pixels, one sphere, one light) for tests of the command line.
inline const std::string kSmallScene =
    "102 0 0 5 0 0 0 1 0 0 0 1 0 8 6\n"
    "101 2 3 4 20 20 20\n103 .1 .1 .1\n"
    "1 1 0 0 0 100 1 .5 .25 .5 10 .8 0 1\n";

// A scene slow enough to be caught mid-render with -s 8 (1000 x 1000 pixels, 64 rays each).
inline const std::string kSlowScene =
    "102 0 0 5 0 0 0 1 0 0 0 1 0 1000 1000\n"
    "101 2 3 4 20 20 20\n1 1 0 0 0 100 1 .5 .25 .5 10 .8 .5 1.5\n";

struct RunResult {
    int status = -1;
    std::string out;
    std::string err;
};

inline std::string read_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

inline void write_file(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

// The files in `dir` whose extension is `extension` (".in"), sorted, so that every test
// walks a corpus in the same order.
inline std::vector<std::filesystem::path> files_with_extension(const std::filesystem::path& dir,
                                                               const std::string& extension) {
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        if (entry.path().extension() == extension) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

// The temporary files rt::OutputFile left in `dir` (NAME.tmp-XXXXXX): litter, once a program
// has ended.
inline std::vector<std::string> litter(const std::filesystem::path& dir) {
    std::vector<std::string> found;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        if (entry.path().filename().string().find(".tmp-") != std::string::npos)
            found.push_back(entry.path().filename().string());
    return found;
}

// Runs a command through the shell: its status as std::system gives it.
inline int shell(const std::string& command) { return std::system(command.c_str()); }

// Whether `program` is on PATH: tests that need make, xargs or groff skip without them.
inline bool on_path(const std::string& program) {
    return shell("command -v '" + program + "' >/dev/null 2>&1") == 0;
}

// A scratch directory of the test's own, emptied first.
inline std::filesystem::path work_dir(const std::string& name) {
    const std::filesystem::path dir = std::filesystem::path(RT_TEST_WORK_DIR) / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// Runs `program <args>` in `dir` (args are passed to the shell as written); its output goes
// through files named after the program's base name.
inline RunResult run_program(const std::string& program, const std::filesystem::path& dir,
                             const std::string& args) {
    const std::string base = std::filesystem::path(program).filename().string();
    const std::string command = "cd '" + dir.string() + "' && '" + program + "' " + args + " >" +
                                base + ".out 2>" + base + ".err; echo $? >" + base + ".status";
    RunResult result;
    if (std::system(command.c_str()) != 0) return result;
    result.status = std::atoi(read_file(dir / (base + ".status")).c_str());
    result.out = read_file(dir / (base + ".out"));
    result.err = read_file(dir / (base + ".err"));
    return result;
}

// The rt the tests run: the one just built, or RT_TEST_BINARY when set, so that the same
// tests can be run against an installed rt or an older one (to see a test fail without its
// fix).
inline std::string rt_binary() {
    const char* other = std::getenv("RT_TEST_BINARY");
    return other != nullptr && *other != '\0' ? other : RT_BINARY;
}

inline RunResult run_rt(const std::filesystem::path& dir, const std::string& args) {
    return run_program(rt_binary(), dir, args);
}

inline RunResult run_rtimg(const std::filesystem::path& dir, const std::string& args) {
    return run_program(RTIMG_BINARY, dir, args);
}

}  // namespace rt_test
