// Installed like a Unix tool: cmake --install puts the programs, the man page, the docs and
// the example scenes where they belong, and the man page describes every option and renders
// without warnings.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "check.h"
#include "cli_util.h"

namespace fs = std::filesystem;
using namespace rt_test;

TEST(cmake_install_puts_everything_in_place) {
    const fs::path prefix = work_dir("install") / "prefix";
    const fs::path log = prefix.parent_path() / "install.log";
    CHECK_EQ(shell(join("'", RT_CMAKE_COMMAND, "' --install '", RT_BUILD_DIR, "' --prefix '",
                        prefix.string(), "' >'", log.string(), "' 2>&1")),
             0);
    for (const char* file :
         {"bin/rt", "bin/rtimg", "share/man/man1/rt.1", "share/man/man1/rtpp.1",
          "share/man/man1/rtimg.1", "share/doc/rt/rtimg.md", "share/doc/rt/README.md",
          "share/doc/rt/format.md", "share/doc/rt/cli.md", "share/doc/rt/architecture.md",
          "share/doc/rt/scenes/showcase.in", "share/doc/rt/scenes/textures/letter-f.ppm"}) {
        if (!fs::exists(prefix / file))
            record_failure(__FILE__, __LINE__, join(file, " was not installed"));
    }
    // The installed program runs.
    const fs::path out = prefix.parent_path() / "version.txt";
    CHECK_EQ(shell(join("'", (prefix / "bin/rt").string(), "' --version >'", out.string(), "'")),
             0);
    CHECK_CONTAINS(read_file(out), "rt ");
    CHECK_EQ(shell(join("'", (prefix / "bin/rtimg").string(), "' --version >'", out.string(), "'")),
             0);
    CHECK_CONTAINS(read_file(out), "rtimg ");
}

namespace {

// Every long option `binary --help` lists appears in the page, where troff writes '-' as '\-'.
void check_page_describes_help(const std::string& binary, const std::string& page_name,
                               int at_least) {
    const std::string page = read_file(fs::path(RT_SOURCE_DIR) / "docs" / page_name);
    const fs::path dir = work_dir("manpage");
    const fs::path help_file = dir / "help.txt";
    CHECK_EQ(shell(join("'", binary, "' --help >'", help_file.string(), "'")), 0);
    std::istringstream lines(read_file(help_file));
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
            record_failure(__FILE__, __LINE__, join(page_name, " does not describe ", option));
    }
    CHECK(options >= at_least);
}

}  // namespace

TEST(the_man_page_describes_every_option_of_help) {
    check_page_describes_help(RT_BINARY, "rt.1", 20);
}

TEST(rtimgs_man_page_describes_every_option_of_its_help) {
    check_page_describes_help(RTIMG_BINARY, "rtimg.1", 7);
}

TEST(rtpps_man_page_describes_every_option_of_its_help) {
    check_page_describes_help(RTPP_BINARY, "rtpp.1", 4);
}

// Each page names the other two programs' pages.
TEST(the_man_pages_refer_to_each_other) {
    const std::vector<std::string> programs{"rt", "rtpp", "rtimg"};
    for (const std::string& program : programs) {
        const std::string page = read_file(fs::path(RT_SOURCE_DIR) / "docs" / (program + ".1"));
        const std::string see_also = page.substr(std::min(page.find(".SH SEE ALSO"), page.size()));
        for (const std::string& other : programs)
            if (other != program && see_also.find(".BR " + other + " (1)") == std::string::npos)
                record_failure(__FILE__, __LINE__,
                               join(program, ".1's SEE ALSO does not name ", other, "(1)"));
    }
}

TEST(the_man_page_renders_without_warnings_where_groff_is_installed) {
    if (!on_path("groff")) {
        std::cout << "groff is not installed: not checked\n";
        return;
    }
    const fs::path log = work_dir("groff") / "groff.log";
    for (const char* name : {"rt.1", "rtpp.1", "rtimg.1"}) {
        const std::string page = (fs::path(RT_SOURCE_DIR) / "docs" / name).string();
        for (const char* device : {"ascii", "utf8"}) {
            CHECK_EQ(
                shell(join("groff -man -ww -z -T", device, " '", page, "' 2>'", log.string(), "'")),
                0);
            CHECK_EQ(read_file(log), "");
        }
    }
}
