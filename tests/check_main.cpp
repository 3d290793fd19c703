#include <chrono>
#include <exception>
#include <iomanip>

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
        const auto start = std::chrono::steady_clock::now();
        try {
            test.body();
        } catch (const std::exception& e) {
            rt_test::record_failure(test.name, 0, std::string("unexpected exception: ") + e.what());
        }
        const bool passed = rt_test::failure_count() == before;
        if (!passed) ++failed_tests;
        // The time of the slow ones, so that a test that grows past its share of CI shows.
        const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
        std::cout << (passed ? "[ ok ] " : "[FAIL] ") << test.name;
        if (took.count() >= 0.5)
            std::cout << " (" << std::fixed << std::setprecision(1) << took.count() << " s)";
        std::cout << "\n";
    }
    const auto total = rt_test::registry().size();
    std::cout << total - static_cast<std::size_t>(failed_tests) << " passed, " << failed_tests
              << " failed\n";
    return failed_tests == 0 && total > 0 ? 0 : 1;
}
