// The polynomial solver against polynomials built from known roots.
//
// Tolerances. The solver sees the coefficients of (x - r1)...(x - rn) rounded to doubles, so
// even exact arithmetic could only find the roots of that rounded polynomial. A root r of
// multiplicity m then moves by about (eps S / |q(r)|)^(1/m), where S = sum |c_i r^i| is the
// size of the terms that rounding perturbs and q is the product of (r - r_k) over the other
// roots (p^(m)(r) / m!). The tests compute that unit from the exact roots, bounding S by
// the product of (|r| + |r_k|), which also covers cancellation inside the expanded
// coefficients, and allow kSimpleRootUnits of it for simple roots (expansion rounding of a
// few eps per coefficient, Horner's rule 2n eps, Newton stopping within that) and
// kMultipleRootUnits for multiple ones, whose constant enters under the m-th root.
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "check.h"
#include "primitives/polynomial.h"

using namespace rt;
using namespace rt_test;

namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
// Units of the rounding sensitivity allowed per root (see the header comment).
// Observed worst cases are about 1.4 (simple) and 2 (multiple) units; the margin keeps the
// tests independent of the compiler's contraction and libm's last bit.
constexpr double kSimpleRootUnits = 16;
constexpr double kMultipleRootUnits = 16;

// The largest error seen so far, in units of the sensitivity, for the report at the end.
double worst_simple_units = 0;
double worst_multiple_units = 0;

struct ComplexPair {
    double re, im;
};

// A polynomial given by its roots: real ones (repeated for multiplicity) and complex pairs.
struct KnownRoots {
    std::vector<double> real;
    std::vector<ComplexPair> pairs;
    double scale = 1;  // the leading coefficient

    // Coefficients, c[i] multiplying x^i, multiplied out in double precision.
    std::vector<double> coefficients() const {
        std::vector<double> c{scale};
        auto multiply = [&c](const std::vector<double>& factor) {
            std::vector<double> product(c.size() + factor.size() - 1, 0.0);
            for (std::size_t i = 0; i < c.size(); ++i)
                for (std::size_t j = 0; j < factor.size(); ++j) product[i + j] += c[i] * factor[j];
            c = product;
        };
        for (double r : real) multiply({-r, 1});
        for (const ComplexPair& z : pairs) multiply({z.re * z.re + z.im * z.im, -2 * z.re, 1});
        return c;
    }

    // The distance a root may move under rounding (the header comment's unit).
    double sensitivity(double r) const {
        int multiplicity = 0;
        double terms = 1, others = 1;
        for (double s : real) {
            terms *= std::fabs(r) + std::fabs(s);
            if (s == r)
                ++multiplicity;
            else
                others *= std::fabs(r - s);
        }
        for (const ComplexPair& z : pairs) {
            terms *= r * r + 2 * std::fabs(z.re * r) + z.re * z.re + z.im * z.im;
            others *= (r - z.re) * (r - z.re) + z.im * z.im;
        }
        return std::pow(kEpsilon * terms / others, 1.0 / multiplicity);
    }
};

// Solves the polynomial and checks the count and every root; returns false on a failure so
// that random tests can say which case failed.
bool check_roots(const KnownRoots& known, int line) {
    const std::vector<double> c = known.coefficients();
    const Roots found = solve_polynomial(c);
    std::vector<double> expected = known.real;
    std::sort(expected.begin(), expected.end());
    bool ok = found.count == static_cast<int>(expected.size());
    for (int i = 1; i < found.count; ++i) ok = ok && found[i - 1] <= found[i];
    for (int i = 0; ok && i < found.count; ++i) {
        const double r = expected[static_cast<std::size_t>(i)];
        const bool simple = std::count(expected.begin(), expected.end(), r) == 1;
        const double error = std::fabs(found[i] - r);
        const double units = error == 0 ? 0 : error / known.sensitivity(r);
        double& worst = simple ? worst_simple_units : worst_multiple_units;
        worst = std::max(worst, units);
        ok = units <= (simple ? kSimpleRootUnits : kMultipleRootUnits);
    }
    if (!ok) {
        std::ostringstream message;
        message.precision(17);
        message << "line " << line << ": roots of";
        for (double x : c) message << ' ' << x;
        message << " (ascending powers): expected";
        for (double r : expected) message << ' ' << r;
        message << ", found";
        for (double r : found) message << ' ' << r;
        record_failure(__FILE__, line, message.str());
    }
    return ok;
}

KnownRoots roots_of(std::vector<double> real, std::vector<ComplexPair> pairs = {},
                    double scale = 1) {
    return {std::move(real), std::move(pairs), scale};
}

#define CHECK_ROOTS(...) check_roots(roots_of(__VA_ARGS__), __LINE__)

}  // namespace

TEST(linear_and_constant) {
    CHECK_ROOTS({2.5}, {}, 4);
    CHECK_ROOTS({-1e-9}, {}, 1e-3);
    CHECK_EQ(solve_polynomial(std::vector<double>{3}).count, 0);
    CHECK_EQ(solve_polynomial(std::vector<double>{0, 0, 0, 0, 0}).count, 0);
    CHECK_EQ(solve_polynomial(std::vector<double>{}).count, 0);
    CHECK_EQ(solve_polynomial(std::vector<double>{1, 1, 1, 1, 1, 1}).count, 0);  // degree 5
}

TEST(simple_roots) {
    CHECK_ROOTS({1, 2});
    CHECK_ROOTS({-3, 0.25}, {}, -2);
    CHECK_ROOTS({1, 2, 3});
    CHECK_ROOTS({-1, 0.5, 7}, {}, 3);
    CHECK_ROOTS({1, 2, 3, 4});
    CHECK_ROOTS({-2, -1, 1, 2});
    CHECK_ROOTS({-0.7, 0.1, 0.3, 11}, {}, -0.5);
    // The convenience forms take the highest power first.
    const Roots q = solve_quartic(1, -10, 35, -50, 24);
    CHECK_EQ(q.count, 4);
    for (int i = 0; i < q.count; ++i) CHECK_NEAR(q[i], i + 1.0, 1e-13);
    const Roots c = solve_cubic(2, -12, 22, -12);
    CHECK_EQ(c.count, 3);
    for (int i = 0; i < c.count; ++i) CHECK_NEAR(c[i], i + 1.0, 1e-13);
    const Roots s = solve_quadratic(1, 0, -4);
    CHECK_EQ(s.count, 2);
    CHECK_NEAR(s[0], -2.0, 1e-15);
    CHECK_NEAR(s[1], 2.0, 1e-15);
}

// Roots 1 and 1 + 2^-29 of x^2 - 2h x + c with h = 1 + 2^-30: h^2 - c = 2^-60 is lost when
// h^2 is rounded before subtracting (a false double root at h), kept by the fused
// multiply-add. Every number here is exact, so the roots must be too.
TEST(close_roots_of_a_quadratic_are_resolved) {
    const double h = 1 + std::ldexp(1.0, -30);
    const double upper = 1 + std::ldexp(1.0, -29);
    const Roots r = solve_quadratic(1, -2 * h, upper);
    CHECK_EQ(r.count, 2);
    CHECK_EQ(r[0], 1.0);
    CHECK_EQ(r[1], upper);
}

TEST(zero_roots_are_exact) {
    const Roots r = solve_quartic(1, 0, -1, 0, 0);  // x^2 (x - 1)(x + 1)
    CHECK_EQ(r.count, 4);
    CHECK_EQ(r[1], 0.0);
    CHECK_EQ(r[2], 0.0);
    CHECK_NEAR(r[0], -1.0, 1e-15);
    CHECK_NEAR(r[3], 1.0, 1e-15);
    const Roots x4 = solve_quartic(2, 0, 0, 0, 0);
    CHECK_EQ(x4.count, 4);
    for (double x : x4) CHECK_EQ(x, 0.0);
    CHECK_ROOTS({0, 0, 0, 3});
}

TEST(double_roots) {
    CHECK_ROOTS({1, 1});
    CHECK_ROOTS({0.1, 0.1});
    CHECK_ROOTS({-1e-3, -1e-3}, {}, 7);
    CHECK_ROOTS({1, 1, 3});
    CHECK_ROOTS({0.1, 0.1, -0.7});
    CHECK_ROOTS({-5, 0.3, 0.3});
    CHECK_ROOTS({1, 1, 2, 3});
    CHECK_ROOTS({-1, 0.2, 0.2, 3});
    CHECK_ROOTS({-4, -1, 2.5, 2.5});
    CHECK_ROOTS({1, 1, 2, 2});
    CHECK_ROOTS({-0.3, -0.3, 0.3, 0.3});
    CHECK_ROOTS({0.1, 0.1, 0.7, 0.7});
    CHECK_ROOTS({0.6, 0.6}, {{1, 2}});
    CHECK_ROOTS({-1e3, -1e3}, {{0.5, 0.1}});
    CHECK_ROOTS({1e-3, 1e-3, 1e3, 1e3});
}

TEST(triple_and_quadruple_roots) {
    CHECK_ROOTS({2, 2, 2});
    CHECK_ROOTS({0.1, 0.1, 0.1});
    CHECK_ROOTS({-0.3, -0.3, -0.3}, {}, 5);
    CHECK_ROOTS({0.1, 0.1, 0.1, 2});
    CHECK_ROOTS({-3, 0.7, 0.7, 0.7});
    CHECK_ROOTS({1, 1, 1, 1});
    CHECK_ROOTS({0.1, 0.1, 0.1, 0.1});
    CHECK_ROOTS({-3.7, -3.7, -3.7, -3.7});
    CHECK_ROOTS({1e3, 1e3, 1e3, 1e3});
    CHECK_ROOTS({1e-3, 1e-3, 1e-3, 1e-3}, {}, 0.5);
}

TEST(roots_spread_over_orders_of_magnitude) {
    CHECK_ROOTS({1e-6, 1e6});
    CHECK_ROOTS({1e-6, 1, 1e6});
    CHECK_ROOTS({-1e6, 1e-6, 3e-6});
    CHECK_ROOTS({1e-6, 1e-3, 1e3, 1e6});
    CHECK_ROOTS({1e-6, 2e-6, 1e6, 2e6});
    CHECK_ROOTS({-1e-6, 1e-6, -1e6, 1e6});
    CHECK_ROOTS({-3e-6, 1e-5, 7e5, 1e6});
    CHECK_ROOTS({1e-6, 1e6}, {{1, 1}});
    CHECK_ROOTS({1e-6, 2e-6}, {{1e5, 1e5}});
    CHECK_ROOTS({1e5, 1e6}, {{1e-5, 1e-5}});
}

TEST(no_real_roots) {
    CHECK_ROOTS({}, {{0, 1}});
    CHECK_ROOTS({}, {{3, 1e-3}});
    CHECK_ROOTS({}, {{0, 1}, {0, 2}});
    CHECK_ROOTS({}, {{-1, 2}, {1, 1}});
    CHECK_ROOTS({}, {{1, 1e-3}, {1, 1e-3}});  // a double complex pair near the axis
    CHECK_ROOTS({}, {{1e-6, 1e-6}, {1e6, 1e6}});
    CHECK_EQ(solve_quartic(1, 0, 0, 0, 1).count, 0);
    CHECK_EQ(solve_quadratic(1, -2, 1 + 1e-6).count, 0);  // (x - 1)^2 + 1e-6
}

TEST(near_zero_leading_coefficient) {
    // A leading term that cannot change the other roots beyond rounding is dropped...
    const Roots cubic = solve_quartic(1e-30, 1, -6, 11, -6);
    CHECK_EQ(cubic.count, 3);
    for (int i = 0; i < cubic.count; ++i) CHECK_NEAR(cubic[i], i + 1.0, 1e-13);
    const Roots zero = solve_quartic(0, 1, -6, 11, -6);
    CHECK_EQ(zero.count, 3);
    const Roots linear = solve_quadratic(1e-20, 1, -1);
    CHECK_EQ(linear.count, 1);
    CHECK_NEAR(linear[0], 1.0, 1e-15);
    const Roots two_down = solve_quartic(1e-300, 0, 1, -3, 2);
    CHECK_EQ(two_down.count, 2);
    CHECK_NEAR(two_down[0], 1.0, 1e-15);
    CHECK_NEAR(two_down[1], 2.0, 1e-15);
    // ...but a small one that still matters is kept, with its large root: 1e-10 x^4 plus
    // (x - 1)(x - 2)(x - 3) has a fourth root near -1e10 - 6.
    const Roots kept = solve_quartic(1e-10, 1, -6, 11, -6);
    CHECK_EQ(kept.count, 4);
    if (kept.count == 4) {
        CHECK_NEAR(kept[0], -1e10 - 6, 1e-4);
        for (int i = 1; i < 4; ++i) CHECK_NEAR(kept[i], i, 1e-8);
    }
    // Small coefficients throughout are not negligible: only relative sizes matter.
    const Roots tiny = solve_quadratic(1e-200, -3e-200, 2e-200);
    CHECK_EQ(tiny.count, 2);
    if (tiny.count == 2) {
        CHECK_NEAR(tiny[0], 1.0, 1e-15);
        CHECK_NEAR(tiny[1], 2.0, 1e-15);
    }
}

// Roots of random magnitude 10^(-6..6) and sign, so many sets span twelve orders of
// magnitude. Sets with nearly coincident roots (condition beyond 1e8, where rounding could
// legitimately merge two roots into a complex pair) are drawn again; multiple roots have
// their own tests.
TEST(random_root_sets) {
    Random random(2024);
    int checked = 0, failed = 0;
    auto magnitude = [&](double lo, double hi) {
        return std::copysign(std::pow(10.0, random.uniform(lo, hi)), random.uniform() - 0.5);
    };
    while (checked < 8000) {
        KnownRoots known;
        const int degree = 1 + checked % 4;
        const bool wide = checked % 3 != 0;
        const double lo = wide ? -6 : -1, hi = wide ? 6 : 1;
        int remaining = degree;
        // A quarter of the sets with degree >= 2 include a complex pair.
        if (degree >= 2 && random.uniform() < 0.25) {
            const double radius = std::fabs(magnitude(lo, hi));
            const double angle = random.uniform(0.01, 3.13);
            known.pairs.push_back({radius * std::cos(angle), radius * std::sin(angle)});
            remaining -= 2;
        }
        for (int i = 0; i < remaining; ++i) known.real.push_back(magnitude(lo, hi));
        known.scale = magnitude(-3, 3);
        bool well_separated = true;
        for (double r : known.real)
            well_separated = well_separated && known.sensitivity(r) < 1e8 * kEpsilon * std::fabs(r);
        if (!well_separated) continue;
        ++checked;
        if (!check_roots(known, __LINE__) && ++failed > 10) break;  // enough to diagnose
    }
    CHECK_EQ(checked, 8000);
    std::cout << "worst simple root error: " << worst_simple_units << " units\n";
}

// Random double, triple and quadruple roots beside other roots.
TEST(random_multiple_roots) {
    Random random(77);
    int failed = 0;
    for (int i = 0; i < 3000 && failed <= 10; ++i) {
        KnownRoots known;
        const double r =
            std::copysign(std::pow(10.0, random.uniform(-3, 3)), random.uniform() - 0.5);
        const int multiplicity = 2 + i % 3;
        known.real.assign(static_cast<std::size_t>(multiplicity), r);
        // The rest of the degree-4 polynomial: distinct real roots or a complex pair, at
        // least 10% away from r so they do not join the cluster.
        if (multiplicity == 2 && i % 2 == 0) {
            const double radius = std::fabs(r) * random.uniform(0.1, 10);
            const double angle = random.uniform(0.1, 3.04);
            known.pairs.push_back({radius * std::cos(angle), radius * std::sin(angle)});
        } else {
            for (int k = multiplicity; k < 4; ++k) {
                double s = 0;
                do {
                    s = r * random.uniform(-10, 10);
                } while (std::fabs(s - r) < 0.1 * std::fabs(r) ||
                         std::any_of(known.real.begin(), known.real.end(), [&](double t) {
                             return std::fabs(s - t) < 0.1 * std::fabs(r);
                         }));
                known.real.push_back(s);
            }
        }
        if (!check_roots(known, __LINE__)) ++failed;
    }
    CHECK_EQ(failed, 0);
    std::cout << "worst multiple root error: " << worst_multiple_units << " units\n";
}

// Two nearly equal roots (relative gap 1e-4 .. 1e-1) beside roots many orders of magnitude
// away: the closed forms alone lose the pair's small gap under the large roots' rounding.
TEST(random_close_pairs_beside_far_roots) {
    Random random(5);
    int failed = 0;
    auto magnitude = [&](double lo, double hi) {
        return std::copysign(std::pow(10.0, random.uniform(lo, hi)), random.uniform() - 0.5);
    };
    for (int i = 0; i < 3000 && failed <= 10; ++i) {
        KnownRoots known;
        const double r = magnitude(-6, 6);
        known.real = {r, r * (1 + std::pow(10.0, random.uniform(-4, -1)))};
        if (i % 3 == 0) {
            known.real.push_back(magnitude(-6, 6));  // a cubic
        } else if (i % 3 == 1) {
            known.real.push_back(magnitude(-6, 6));
            known.real.push_back(magnitude(-6, 6));
        } else {
            const double radius = std::fabs(magnitude(-6, 6));
            const double angle = random.uniform(0.01, 3.13);
            known.pairs.push_back({radius * std::cos(angle), radius * std::sin(angle)});
        }
        bool well_separated = true;
        for (double x : known.real)
            well_separated = well_separated && known.sensitivity(x) < 1e8 * kEpsilon * std::fabs(x);
        if (!well_separated) continue;
        if (!check_roots(known, __LINE__)) ++failed;
    }
    CHECK_EQ(failed, 0);
}

// The solver's cube roots and trisections use no function of the C library (cbrt, cos, acos
// round their last bit differently on other machines): its own, from correctly rounded
// operations, must be as accurate. x^3 = a has the one real root cbrt(a), through Cardano's
// branch (over the exponents where the solver keeps x^3 beside the constant: beyond about
// 2^52 it drops the leading term as negligible); (x - 1)(x - 2)(x - 3) and its kin with three real
// roots go through the trigonometric one.
TEST(cube_roots_and_trisections_need_no_library_rounding) {
    double worst = 0;
    for (int e = -150; e <= 48; ++e)
        for (const double m : {1.0, 1.1, 1.5, 1.9, 2.0, 3.7, 5.0, 7.99}) {
            for (const double sign : {1.0, -1.0}) {
                const double a = sign * std::ldexp(m, e);
                const Roots r = solve_cubic(1, 0, 0, -a);
                CHECK_EQ(r.count, 1);
                if (r.count != 1) continue;
                const double exact = std::cbrt(a);
                worst = std::max(worst, std::fabs(r[0] - exact) / std::fabs(exact));
            }
        }
    CHECK(worst <= 2 * std::numeric_limits<double>::epsilon());
    for (const double scale : {1e-30, 1e-3, 1.0, 7.0, 1e3, 1e30}) {
        const double a = scale, b = 2 * scale, c = 3 * scale;
        // (x - a)(x - b)(x - c) = x^3 - 6s x^2 + 11 s^2 x - 6 s^3, s = scale.
        const Roots r = solve_cubic(1, -(a + b + c), a * b + b * c + a * c, -(a * b * c));
        CHECK_EQ(r.count, 3);
        if (r.count != 3) continue;
        // Condition numbers 12, 30 and 20 (sum |c_i x^i| / |x p'(x)|): a few eps times those.
        CHECK_NEAR(r[0] / a, 1, 4 * 12 * std::numeric_limits<double>::epsilon());
        CHECK_NEAR(r[1] / b, 1, 4 * 30 * std::numeric_limits<double>::epsilon());
        CHECK_NEAR(r[2] / c, 1, 4 * 20 * std::numeric_limits<double>::epsilon());
    }
}
