// rt's own small test helper: TEST registers a function, CHECK and friends report failures
// with file and line and keep going, and main() (from check_main.cpp) runs every test and
// exits non-zero when any check failed.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "rt/error.h"
#include "rt/spectrum.h"
#include "rt/vec.h"

namespace rt_test {

struct TestCase {
    const char* name;
    std::function<void()> body;
};

std::vector<TestCase>& registry();
void record_failure(const char* file, int line, const std::string& message);
int failure_count();
// The test program's command-line arguments (after its name).
std::vector<std::string>& arguments();

struct Registrar {
    Registrar(const char* name, std::function<void()> body) {
        registry().push_back({name, std::move(body)});
    }
};

// Values as failure messages show them, with full precision. (Built with a stream: g++ 12
// warns falsely about "literal" + std::string chains.)
template <typename... Parts>
std::string join(const Parts&... parts) {
    std::ostringstream s;
    s.precision(17);
    (s << ... << parts);
    return s.str();
}
inline std::string show(double v) { return join(v); }
inline std::string show(const rt::Vec3& v) { return join('(', v.x, ", ", v.y, ", ", v.z, ')'); }
inline std::string show(const rt::Spectrum& v) {
    return join('[', v[0], ", ", v[1], ", ", v[2], ']');
}

inline bool near(double a, double b, double tolerance) { return std::fabs(a - b) <= tolerance; }
inline bool near(const rt::Vec3& a, const rt::Vec3& b, double tolerance) {
    return near(a.x, b.x, tolerance) && near(a.y, b.y, tolerance) && near(a.z, b.z, tolerance);
}
inline bool near(const rt::Spectrum& a, const rt::Spectrum& b, double tolerance) {
    for (std::size_t i = 0; i < rt::kSpectrumComponents; ++i)
        if (!near(a[i], b[i], tolerance)) return false;
    return true;
}

// A seeded generator whose sequence is the same on every platform (the standard fixes
// mt19937_64's output but not the distributions').
class Random {
  public:
    explicit Random(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next() {
        // splitmix64
        std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    rt::Vec3 in_box(double half) {
        return {uniform(-half, half), uniform(-half, half), uniform(-half, half)};
    }
    rt::Vec3 unit_vector() {
        for (;;) {
            const rt::Vec3 v = in_box(1);
            const double l2 = rt::dot(v, v);
            if (l2 > 1e-6 && l2 <= 1) return v / std::sqrt(l2);
        }
    }

  private:
    std::uint64_t state_;
};

}  // namespace rt_test

#define RT_TEST_CONCAT2(a, b) a##b
#define RT_TEST_CONCAT(a, b) RT_TEST_CONCAT2(a, b)

#define TEST(name)                                                                 \
    static void name();                                                            \
    static const rt_test::Registrar RT_TEST_CONCAT(registrar_, name)(#name, name); \
    static void name()

#define CHECK(condition)                                                           \
    do {                                                                           \
        if (!(condition)) rt_test::record_failure(__FILE__, __LINE__, #condition); \
    } while (0)

// CHECK_NEAR works for doubles, Vec3 and Spectrum.
#define CHECK_NEAR(actual, expected, tolerance)                                                    \
    do {                                                                                           \
        const auto rt_actual_ = (actual);                                                          \
        const auto rt_expected_ = (expected);                                                      \
        if (!rt_test::near(rt_actual_, rt_expected_, (tolerance)))                                 \
            rt_test::record_failure(__FILE__, __LINE__,                                            \
                                    std::string(#actual " = ") + rt_test::show(rt_actual_) +       \
                                        ", expected " + rt_test::show(rt_expected_) + " within " + \
                                        rt_test::show(tolerance));                                 \
    } while (0)

#define CHECK_EQ(actual, expected)                                                       \
    do {                                                                                 \
        const auto rt_actual_ = (actual);                                                \
        const auto rt_expected_ = (expected);                                            \
        if (!(rt_actual_ == rt_expected_)) {                                             \
            std::ostringstream rt_message_;                                              \
            rt_message_ << #actual " = " << rt_actual_ << ", expected " << rt_expected_; \
            rt_test::record_failure(__FILE__, __LINE__, rt_message_.str());              \
        }                                                                                \
    } while (0)

// Checks that a string contains a piece.
#define CHECK_CONTAINS(text, piece)                                                             \
    do {                                                                                        \
        const std::string rt_text_ = (text);                                                    \
        const std::string rt_piece_ = (piece);                                                  \
        if (rt_text_.find(rt_piece_) == std::string::npos)                                      \
            rt_test::record_failure(__FILE__, __LINE__,                                         \
                                    "'" + rt_text_ + "' does not contain '" + rt_piece_ + "'"); \
    } while (0)

namespace rt_test {

// The message of the rt::Error the call throws, or "no error".
inline std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const rt::Error& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace rt_test

// Checks that evaluating an expression throws rt::Error with exactly this message.
#define CHECK_ERROR(expression, message) \
    CHECK_EQ(rt_test::error_of([&] { (void)(expression); }), std::string(message))
