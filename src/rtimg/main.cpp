// rtimg: compares, merges, converts and describes images (docs/rtimg.md).
#include <cstring>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "rt/error.h"
#include "common/message_text.h"
#include "rtimg.h"

int main(int argc, char** argv) {
    const std::vector<std::string> args(argv + 1, argv + argc);
    const std::string command = args.empty() ? "" : args[0];
    if (command == "-h" || command == "--help") {
        std::cout << rtimg::usage_text();
        return std::cout.flush() ? rtimg::kExitOk : rtimg::kExitFail;
    }
    if (command == "-V" || command == "--version") {
        std::cout << "rtimg " RT_VERSION "\n";
        return std::cout.flush() ? rtimg::kExitOk : rtimg::kExitFail;
    }
    const std::vector<std::string> rest(args.empty() ? args.end() : args.begin() + 1, args.end());
    // diff reports every error as 2, so that 1 always means "the images differ".
    const int error_status = command == "diff" ? rtimg::kExitUsage : rtimg::kExitFail;
    try {
        if (command == "diff") return rtimg::diff(rest);
        if (command == "merge") return rtimg::merge(rest);
        if (command == "convert") return rtimg::convert(rest);
        if (command == "info") return rtimg::info(rest);
        throw rtimg::UsageError{command.empty() ? "no command given"
                                                : "unknown command " + rt::quote_token(command)};
    } catch (const rtimg::UsageError& e) {
        std::cerr << "rtimg: " << rt::printable_message(e.message)
                  << "\nTry 'rtimg --help' for more information.\n";
        return rtimg::kExitUsage;
    } catch (const std::bad_alloc&) {
        std::cerr << "rtimg: out of memory\n";
    } catch (const std::exception& e) {
        std::cerr << "rtimg: " << rt::printable_message(e.what()) << "\n";
    }
    return error_status;
}
