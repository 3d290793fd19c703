// rtimg: compares, merges, converts and describes images (docs/rtimg.md).
#include <string>
#include <vector>

#include "common/exit_status.h"
#include "common/message_text.h"
#include "rtimg.h"

int main(int argc, char** argv) {
    const std::vector<std::string> args(argv + 1, argv + argc);
    const std::string command = args.empty() ? "" : args[0];
    const std::vector<std::string> rest(args.empty() ? args.end() : args.begin() + 1, args.end());
    // diff reports every error as 2, so that 1 always means "the images differ".
    const rt::ProgramErrors program{
        .name = "rtimg",
        .error_status = command == "diff" ? rt::kExitUsage : rt::kExitError,
        .name_located_errors = true};
    return rt::run_guarded(program, [&] {
        if (command == "-h" || command == "--help")
            return rt::print_to_stdout("rtimg", rtimg::usage_text());
        if (command == "-V" || command == "--version")
            return rt::print_to_stdout("rtimg", "rtimg " RT_VERSION "\n");
        if (command == "diff") return rtimg::diff(rest);
        if (command == "merge") return rtimg::merge(rest);
        if (command == "convert") return rtimg::convert(rest);
        if (command == "info") return rtimg::info(rest);
        throw rtimg::UsageError{command.empty() ? "no command given"
                                                : "unknown command " + rt::quote_token(command)};
    });
}
