#include <exception>

#include "check.h"

namespace rt_test {

namespace {
int failures = 0;
}

std::vector<TestCase>& registry() {
    static std::vector<TestCase> tests;
    return tests;
}

void record_failure(const char* file, int line, const std::string& message) {
    ++failures;
    std::cerr << file << ":" << line << ": check failed: " << message << "\n";
}

int failure_count() { return failures; }

std::vector<std::string>& arguments() {
    static std::vector<std::string> args;
    return args;
}

}  // namespace rt_test

int main(int argc, char** argv) {
    rt_test::arguments().assign(argv + 1, argv + argc);
    int failed_tests = 0;
    for (const rt_test::TestCase& test : rt_test::registry()) {
        const int before = rt_test::failure_count();
        try {
            test.body();
        } catch (const std::exception& e) {
            rt_test::record_failure(test.name, 0, std::string("unexpected exception: ") + e.what());
        }
        const bool passed = rt_test::failure_count() == before;
        if (!passed) ++failed_tests;
        std::cout << (passed ? "[ ok ] " : "[FAIL] ") << test.name << "\n";
    }
    const auto total = rt_test::registry().size();
    std::cout << total - static_cast<std::size_t>(failed_tests) << " passed, " << failed_tests
              << " failed\n";
    return failed_tests == 0 && total > 0 ? 0 : 1;
}
