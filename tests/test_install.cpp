// Installed like a Unix tool: cmake --install puts the programs, the man page, the docs and
// the example scenes where they belong, and the man page describes every option and renders
// without warnings.
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>

#include "check.h"
#include "cli_util.h"

namespace fs = std::filesystem;
using namespace rt_test;

namespace {

int shell(const std::string& command) { return std::system(command.c_str()); }

}  // namespace

TEST(cmake_install_puts_everything_in_place) {
    const fs::path prefix = work_dir("install") / "prefix";
    const fs::path log = prefix.parent_path() / "install.log";
    CHECK_EQ(shell(join("'", RT_CMAKE_COMMAND, "' --install '", RT_BUILD_DIR, "' --prefix '",
                        prefix.string(), "' >'", log.string(), "' 2>&1")),
             0);
    for (const char* file :
         {"bin/rt", "share/man/man1/rt.1", "share/doc/rt/README.md", "share/doc/rt/format.md",
          "share/doc/rt/cli.md", "share/doc/rt/architecture.md", "share/doc/rt/scenes/showcase.in",
          "share/doc/rt/scenes/textures/letter-f.ppm"}) {
        if (!fs::exists(prefix / file))
            record_failure(__FILE__, __LINE__, join(file, " was not installed"));
    }
    // The installed program runs.
    const fs::path out = prefix.parent_path() / "version.txt";
    CHECK_EQ(shell(join("'", (prefix / "bin/rt").string(), "' --version >'", out.string(), "'")),
             0);
    CHECK_CONTAINS(read_file(out), "rt ");
}

TEST(the_man_page_describes_every_option_of_help) {
    const std::string page = read_file(fs::path(RT_SOURCE_DIR) / "docs" / "rt.1");
    const fs::path dir = work_dir("manpage");
    const RunResult help = run_rt(dir, "--help");
    CHECK_EQ(help.status, 0);
    // Every long option --help lists appears in the page, where troff writes '-' as '\-'.
    std::istringstream lines(help.out);
    int options = 0;
    for (std::string line; std::getline(lines, line);) {
        const auto at = line.find("--");
        if (line.rfind("  ", 0) != 0 || at == std::string::npos || at > 8) continue;
        const std::string option = line.substr(at, line.find_first_of(" =", at) - at);
        std::ostringstream troff;
        for (const char c : option) {
            if (c == '-') troff << '\\';
            troff << c;
        }
        ++options;
        if (page.find(troff.str()) == std::string::npos)
            record_failure(__FILE__, __LINE__, join("rt.1 does not describe ", option));
    }
    CHECK(options >= 20);
}

TEST(the_man_page_renders_without_warnings_where_groff_is_installed) {
    if (shell("command -v groff >/dev/null 2>&1") != 0) {
        std::cout << "groff is not installed: not checked\n";
        return;
    }
    const fs::path log = work_dir("groff") / "groff.log";
    const std::string page = (fs::path(RT_SOURCE_DIR) / "docs" / "rt.1").string();
    for (const char* device : {"ascii", "utf8"}) {
        CHECK_EQ(
            shell(join("groff -man -ww -z -T", device, " '", page, "' 2>'", log.string(), "'")), 0);
        CHECK_EQ(read_file(log), "");
    }
}
