// The bad-input corpus (tests/bad, see its README): every case through the real binary, with
// its exact message and exit status, and the output file left as it was.
#include <filesystem>
#include <vector>

#include "check.h"
#include "cli_util.h"

using namespace rt_test;
namespace fs = std::filesystem;

namespace {

struct Expectation {
    std::string args = "{} -o out.ppm";
    int status = 1;
    std::string err;
};

Expectation parse_expectation(const std::string& text) {
    Expectation e;
    std::size_t at = 0;
    while (at < text.size()) {
        const std::size_t end = text.find('\n', at);
        const std::string line = text.substr(at, end - at);
        at = end == std::string::npos ? text.size() : end + 1;
        if (line == "stderr:") {
            e.err = text.substr(at);
            break;
        }
        if (line.rfind("args: ", 0) == 0) e.args = line.substr(6);
        if (line.rfind("status: ", 0) == 0) e.status = std::atoi(line.c_str() + 8);
    }
    return e;
}

constexpr const char* kKeep = "previous image, must survive";

}  // namespace

TEST(every_bad_input_gives_its_message_and_status_and_keeps_the_output) {
    const fs::path corpus = fs::path(RT_SOURCE_DIR) / "tests" / "bad";
    const std::vector<fs::path> cases = files_with_extension(corpus, ".in");
    CHECK(cases.size() >= 30);
    for (const fs::path& input : cases) {
        const fs::path expect_path = fs::path(input).replace_extension(".expect");
        CHECK(fs::exists(expect_path));
        if (!fs::exists(expect_path)) continue;
        const Expectation expect = parse_expectation(read_file(expect_path));
        const fs::path dir = work_dir("bad_inputs");
        const std::string name = input.filename().string();
        fs::copy_file(input, dir / name);
        write_file(dir / "out.ppm", kKeep);
        std::string args = expect.args;
        if (const auto slot = args.find("{}"); slot != std::string::npos)
            args.replace(slot, 2, "'" + name + "'");
        const RunResult r = run_rt(dir, args);
        const auto check = [&](bool ok, const std::string& what) {
            if (!ok) record_failure(__FILE__, __LINE__, name + ": " + what);
        };
        check(r.status == expect.status, join("status ", r.status, ", expected ", expect.status));
        check(r.err == expect.err, "stderr was\n" + r.err + "expected\n" + expect.err);
        check(r.out.empty(), "stdout was " + r.out);
        check(read_file(dir / "out.ppm") == kKeep, "out.ppm was changed");
    }
}
