#include "common/exit_status.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <new>

#include "common/message_text.h"
#include "common/option_reader.h"
#include "rt/error.h"

namespace rt {

int run_guarded(const ProgramErrors& program, const std::function<int()>& work) {
    try {
        return work();
    } catch (const UsageError& e) {
        std::cerr << program.name << ": " << printable_message(e.message) << "\nTry '"
                  << program.name << " --help' for more information.\n";
        return kExitUsage;
    } catch (const Error& e) {
        if (program.name_located_errors) std::cerr << program.name << ": ";
        std::cerr << printable_message(e.what()) << "\n";
    } catch (const std::bad_alloc&) {
        std::cerr << program.name << ": out of memory\n";
    } catch (const std::exception& e) {
        std::cerr << program.name << ": " << printable_message(e.what()) << "\n";
    }
    return program.error_status;
}

int print_to_stdout(std::string_view program, std::string_view text) {
    errno = 0;
    std::cout << text;
    std::cout.flush();
    if (std::cout && std::fflush(stdout) == 0 && !std::ferror(stdout)) return kExitOk;
    const int error = errno;
    std::cerr << program << ": cannot write to standard output" << (error != 0 ? ": " : "")
              << (error != 0 ? std::strerror(error) : "") << "\n";
    return kExitError;
}

}  // namespace rt
