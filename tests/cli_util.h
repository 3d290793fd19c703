// Runs the rt binary through the shell and captures what it printed and its exit status.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace rt_test {

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

// A scratch directory of the test's own, emptied first.
inline std::filesystem::path work_dir(const std::string& name) {
    const std::filesystem::path dir = std::filesystem::path(RT_TEST_WORK_DIR) / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// Runs `rt <args>` in `dir` (args are passed to the shell as written).
inline RunResult run_rt(const std::filesystem::path& dir, const std::string& args) {
    const std::string command = "cd '" + dir.string() + "' && '" RT_BINARY "' " + args +
                                " >rt.out 2>rt.err; echo $? >rt.status";
    RunResult result;
    if (std::system(command.c_str()) != 0) return result;
    result.status = std::atoi(read_file(dir / "rt.status").c_str());
    result.out = read_file(dir / "rt.out");
    result.err = read_file(dir / "rt.err");
    return result;
}

}  // namespace rt_test
