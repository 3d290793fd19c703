// docs/tutorial.md runs as written: its scene fragments, put together in order, make a file
// that its commands render, and the message it quotes is the one rtpp gives for the mistake
// it describes, word for word.
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "check.h"
#include "cli_util.h"
#include "rt/image_file.h"

using namespace rt_test;
namespace fs = std::filesystem;

namespace {

// The page's code blocks (lines indented by four spaces), each as one text.
std::vector<std::string> code_blocks(const std::string& page) {
    std::vector<std::string> blocks;
    std::istringstream lines(page);
    std::string block, pending_blank;
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("    ", 0) == 0) {
            block += pending_blank + line.substr(4) + "\n";
            pending_blank.clear();
        } else if (line.empty() && !block.empty()) {
            pending_blank += "\n";  // a blank line inside a block, unless the block ends
        } else if (!block.empty()) {
            blocks.push_back(block);
            block.clear();
            pending_blank.clear();
        }
    }
    if (!block.empty()) blocks.push_back(block);
    return blocks;
}

bool is_command(const std::string& block) {
    return block.rfind("build/", 0) == 0 || block.rfind("cmake ", 0) == 0;
}

// A command of the page run in `dir`, with build/ standing for this build's programs.
int run_step(const fs::path& dir, const std::string& command, const std::string& log) {
    std::string line = command.substr(0, command.find('\n'));
    for (std::size_t at = line.find("build/"); at != std::string::npos;
         at = line.find("build/", at))
        if (at == 0 || line[at - 1] == ' ') {
            line.replace(at, 6, std::string(RT_BUILD_DIR) + "/");
            at += std::string(RT_BUILD_DIR).size() + 1;
        } else {
            at += 6;
        }
    return shell("cd '" + dir.string() + "' && " + line + " 2>'" + log + "'");
}

}  // namespace

TEST(every_step_of_the_tutorial_runs_as_written) {
    const std::string page = read_file(fs::path(RT_SOURCE_DIR) / "docs" / "tutorial.md");
    const fs::path dir = work_dir("tutorial");
    const std::string log = (dir / "step.err").string();
    std::string scene;
    int commands = 0, fragments = 0;
    for (const std::string& block : code_blocks(page)) {
        if (block.rfind("cmake ", 0) == 0) continue;      // the build: this test runs inside it
        if (block.rfind("first.rts:", 0) == 0) continue;  // the quoted message, checked below
        if (!is_command(block)) {
            scene += block;
            write_file(dir / "first.rts", scene);
            ++fragments;
            continue;
        }
        ++commands;
        CHECK_EQ(run_step(dir, block, log), 0);
        CHECK_EQ(read_file(log), std::string());
        const rt::ImageFile image = rt::read_image_file(dir / "first.ppm");
        CHECK_EQ(image.width(), 480);
        CHECK_EQ(image.height(), 360);
    }
    CHECK(fragments >= 5);
    CHECK(commands >= 2);
}

TEST(the_tutorials_error_message_is_what_rtpp_says) {
    const std::string page = read_file(fs::path(RT_SOURCE_DIR) / "docs" / "tutorial.md");
    std::string scene, quoted;
    for (const std::string& block : code_blocks(page)) {
        if (block.rfind("first.rts:", 0) == 0)
            quoted = block;
        else if (!is_command(block) && quoted.empty())
            scene += block;
    }
    CHECK(!quoted.empty());
    // The mistake the page describes: `radus` for the first sphere's `radius`.
    const std::size_t sphere = scene.find("sphere { radius");
    CHECK(sphere != std::string::npos);
    scene.replace(sphere + 9, 6, "radus");
    const fs::path dir = work_dir("tutorial_error");
    write_file(dir / "first.rts", scene);
    const std::string log = (dir / "rtpp.err").string();
    CHECK(run_step(dir, "build/rtpp first.rts > first.in", log) != 0);
    CHECK_EQ(read_file(log), quoted);
}
