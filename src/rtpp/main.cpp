// rtpp: compiles rt's readable scene language to its numeric scene format.
#include <exception>
#include <iostream>
#include <new>

#include "common/message_text.h"
#include "rtpp/command_line.h"
#include "rtpp/compiler.h"
#include "rtpp/source.h"

namespace {
constexpr int kExitOk = 0;
constexpr int kExitError = 1;  // a scene or input/output error
constexpr int kExitUsage = 2;  // the command line made no sense
}  // namespace

int main(int argc, char** argv) {
    rtpp::CommandLine cl;
    try {
        cl = rtpp::parse_command_line({argv + 1, argv + argc});
    } catch (const rtpp::UsageError& e) {
        std::cerr << "rtpp: " << rt::printable_message(e.message)
                  << "\nTry 'rtpp --help' for more information.\n";
        return kExitUsage;
    }
    if (cl.help) {
        std::cout << rtpp::usage_text();
        return kExitOk;
    }
    if (cl.version) {
        std::cout << "rtpp " RT_VERSION "\n";
        return kExitOk;
    }
    try {
        rtpp::CompileOptions options;
        for (const std::string& dir : cl.include_dirs) options.include_dirs.emplace_back(dir);
        rtpp::write_output(cl.output, rtpp::compile_file(cl.input, options));
        return kExitOk;
    } catch (const rtpp::CompileError& e) {
        std::cerr << rt::printable_message(e.what()) << "\n";
    } catch (const std::bad_alloc&) {
        std::cerr << "rtpp: out of memory\n";
    } catch (const std::exception& e) {
        std::cerr << "rtpp: " << rt::printable_message(e.what()) << "\n";
    }
    return kExitError;
}
