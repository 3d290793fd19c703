// docs/examples/ci works the way its README says a user takes it: a scratch project that
// include()s its CMakeLists.txt gets one CTest test per scene, passing against goldens made by
// golden.sh and failing when a scene changes; golden.sh writes nothing where it is run.
#include <cstdlib>
#include <filesystem>
#include <string>

#include "check.h"
#include "cli_util.h"

namespace fs = std::filesystem;
using namespace rt_test;

namespace {

const fs::path kExample = fs::path(RT_SOURCE_DIR) / "docs" / "examples" / "ci";

// The ctest next to the cmake that configured rt.
std::string ctest_command() {
    return (fs::path(RT_CMAKE_COMMAND).parent_path() / "ctest").string();
}

std::string programs() { return join("RT='", RT_BINARY, "' RTIMG='", RTIMG_BINARY, "' "); }

}  // namespace

TEST(a_project_that_includes_the_example_gets_golden_tests) {
    if (!fs::exists(ctest_command())) {
        std::cout << "no ctest beside cmake: not checked\n";
        return;
    }
    const fs::path project = work_dir("ci_example") / "project";
    fs::create_directories(project / "scenes");
    fs::create_directories(project / "golden");
    fs::copy_file(fs::path(RT_SOURCE_DIR) / "scenes" / "sphere.in", project / "scenes" / "ball.in");
    write_file(project / "CMakeLists.txt",
               join("cmake_minimum_required(VERSION 3.16)\nproject(scratch NONE)\n"
                    "enable_testing()\ninclude(\"",
                    (kExample / "CMakeLists.txt").string(), "\")\n"));
    const fs::path log = project.parent_path() / "log.txt";
    // The golden image, made once; golden.sh without OUTDIR leaves nothing behind it.
    CHECK_EQ(shell(join("cd '", project.string(), "' && ", programs(),
                        "RTFLAGS='--size 40x30' UPDATE=1 '", (kExample / "golden.sh").string(),
                        "' scenes/ball.in golden/ball.png >'", log.string(), "' 2>&1")),
             0);
    CHECK(fs::exists(project / "golden" / "ball.png"));
    CHECK(!fs::exists(project / "golden-out"));
    const fs::path build = project.parent_path() / "build";
    CHECK_EQ(shell(join("'", RT_CMAKE_COMMAND, "' -S '", project.string(), "' -B '", build.string(),
                        "' -DRT_PROGRAM='", RT_BINARY, "' -DRTIMG_PROGRAM='", RTIMG_BINARY, "' >'",
                        log.string(), "' 2>&1")),
             0);
    // RTFLAGS as the golden was made: the test renders at the same size.
    const std::string run =
        join("cd '", build.string(), "' && RTFLAGS='--size 40x30' '", ctest_command(),
             "' --output-on-failure >'", log.string(), "' 2>&1");
    CHECK_EQ(shell(run), 0);
    CHECK_CONTAINS(read_file(log), "golden-ball");
    CHECK_CONTAINS(read_file(log), "100% tests passed");
    CHECK(!fs::exists(project / "golden-out"));
    // The scene changes (a blue ball in front): the test fails and names the heat map.
    write_file(project / "scenes" / "ball.in",
               read_file(project / "scenes" / "ball.in") + "1 0.3 0 0 2 100 0 0 1 0 1 1 0 1\n");
    CHECK(shell(run) != 0);
    CHECK_CONTAINS(read_file(log), "differs from");
    CHECK_CONTAINS(read_file(log), (build / "golden-out" / "ball-diff.png").string());
}
