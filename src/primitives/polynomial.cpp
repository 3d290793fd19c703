// Real roots of polynomials of degree at most 4 (accuracy: see rt/polynomial.h).
//
// The plan, for every degree: find the roots in closed form, polish each real one by Newton's
// method on the polynomial itself, and give each complex pair that rounding may have pushed
// off the real line a chance to come back as a double root. The cubic finds one root in
// closed form and divides it out; the quartic factors into two quadratics (Ferrari, through
// the resolvent cubic) and refines the factors by Newton's method on their coefficients,
// which keeps small roots accurate when others are many orders of magnitude larger.
#include "primitives/polynomial.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rt {

namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

// Polishing stops as soon as a Newton step fails to shrink |p|. The closed forms leave a
// simple root one or two steps from rounding level, so the cap only bounds the (linear)
// convergence at multiple roots, which are no more accurate for more steps.
constexpr int kMaxPolishSteps = 8;

// Newton's method on the factors' coefficients converges quadratically from Ferrari's
// factors; more steps than this mean the factors share a root and it cannot converge.
constexpr int kMaxFactorSteps = 8;

// A complex pair is examined as a possible double real root only when its imaginary part is
// this small beside its real part. Rounding leaves imaginary parts of about eps^(1/m) for a
// root of multiplicity m (about 1e-4 for a quadruple root), well inside this; genuine pairs
// are mostly well outside it and cost nothing.
constexpr double kNearlyRealPair = 1e-2;

// Newton steps on p' towards the critical point under a nearly real pair. They converge
// quadratically at a double root and halve the distance per step at a triple one.
constexpr int kMaxCriticalSteps = 64;

// |p(x)| within this many eps of sum |c_i x^i| is zero as far as rounding can tell: Horner's
// rule on degree n errs by at most about 2n eps times that sum, and the coefficients
// themselves carry an eps each. Twice that margin for degree 4.
constexpr double kRoundingZero = 16;

// A polynomial of degree at most 4: c[i] multiplies x^i.
struct Polynomial {
    double c[5] = {};
    int degree = 0;

    double value(double x) const {
        double v = c[degree];
        for (int i = degree - 1; i >= 0; --i) v = v * x + c[i];
        return v;
    }
    // p(x) and p'(x) together, by Horner's rule.
    void value_and_slope(double x, double& v, double& slope) const {
        v = c[degree];
        slope = 0;
        for (int i = degree - 1; i >= 0; --i) {
            slope = slope * x + v;
            v = v * x + c[i];
        }
    }
    // p'(x) and p''(x).
    void slope_and_curvature(double x, double& slope, double& curvature) const {
        double v = c[degree];
        slope = 0;
        curvature = 0;
        for (int i = degree - 1; i >= 0; --i) {
            curvature = curvature * x + slope;
            slope = slope * x + v;
            v = v * x + c[i];
        }
        curvature *= 2;
    }
    // sum |c_i| |x|^i: the size of the rounding errors in value(x).
    double magnitude(double x) const {
        const double ax = std::fabs(x);
        double m = std::fabs(c[degree]);
        for (int i = degree - 1; i >= 0; --i) m = m * ax + std::fabs(c[i]);
        return m;
    }
};

// The solver uses no function of the C library that is not correctly rounded: cbrt, cos and
// acos round their last bit differently from one machine (and one build of the library) to
// the next, and a root that starts one bit apart can polish to another double. What it uses
// instead is built from +, -, *, / and sqrt, which IEEE 754 rounds alike everywhere, and from
// frexp and ldexp, which are exact.

// Newton steps for the cube root of a number in [0.5, 4) from the line through its ends:
// the first guess is within 10 %, so five steps reach rounding; the sixth settles it.
constexpr int kCubeRootSteps = 6;

// The real cube root of x, the same on every IEEE machine.
double cube_root(double x) {
    if (x == 0 || !std::isfinite(x)) return x;
    int exponent = 0;
    const double mantissa = std::frexp(std::fabs(x), &exponent);  // in [0.5, 1)
    // |x| = m 2^(3k) with m in [0.5, 4): the cube root is cbrt(m) 2^k.
    int rest = exponent % 3;
    if (rest < 0) rest += 3;
    const double m = std::ldexp(mantissa, rest);
    const int k = (exponent - rest) / 3;
    double y = 0.69 + 0.23 * m;
    for (int step = 0; step < kCubeRootSteps; ++step) y -= (y * y * y - m) / (3 * y * y);
    return std::copysign(std::ldexp(y, k), x);
}

// Newton steps for cos(acos(c) / 3) from 1; they descend monotonically (see below) and reach
// rounding within six.
constexpr int kTrisectionSteps = 12;

// cos(acos(c) / 3) for c in [0, 1], without cos or acos: by the triple-angle formula
// cos(3 theta) = 4 cos^3(theta) - 3 cos(theta), it is the largest root y of 4 y^3 - 3 y = c,
// which lies in [cos(30 degrees), 1]. There the cubic is convex with slope at least 6, so
// Newton's method from 1 (where the cubic is 1 - c >= 0) falls monotonically onto the root;
// it stops when a step no longer descends.
double trisected_cosine(double c) {
    double y = 1;
    for (int step = 0; step < kTrisectionSteps; ++step) {
        const double next = y - (y * (4 * y * y - 3) - c) / (12 * y * y - 3);
        if (!(next < y)) break;
        y = next;
    }
    return y;
}

void add_root(Roots& roots, double x) {
    if (roots.count < Roots::kCapacity && std::isfinite(x))
        roots.values[static_cast<std::size_t>(roots.count++)] = x;
}

// |miss| as a fraction of scale, the size of the terms it came from.
double relative(double miss, double scale) { return scale > 0 ? std::fabs(miss) / scale : 0; }

// Newton's method on p from an estimate of a root, kept only while |p| keeps shrinking.
double polish(const Polynomial& p, double x) {
    double v = 0, slope = 0;
    p.value_and_slope(x, v, slope);
    for (int step = 0; step < kMaxPolishSteps && v != 0 && slope != 0; ++step) {
        const double next = x - v / slope;
        double next_v = 0, next_slope = 0;
        p.value_and_slope(next, next_v, next_slope);
        if (!(std::fabs(next_v) < std::fabs(v))) break;
        x = next;
        v = next_v;
        slope = next_slope;
    }
    return x;
}

// A complex pair re +- i im close to the real axis may be a double (or higher) root that
// rounding split into a pair. Follow Newton's method on p' from re to the critical point
// between the would-be roots; if p vanishes there to within rounding, it is a real root.
bool double_root_near(const Polynomial& p, double re, double im, double& root) {
    const double window = kNearlyRealPair * std::fabs(re);
    if (!(im <= window)) return false;
    double x = re;
    for (int step = 0;; ++step) {
        if (std::fabs(p.value(x)) <= kRoundingZero * kEpsilon * p.magnitude(x)) {
            root = x;
            return true;
        }
        if (step == kMaxCriticalSteps) return false;
        double slope = 0, curvature = 0;
        p.slope_and_curvature(x, slope, curvature);
        if (curvature == 0) return false;
        x -= slope / curvature;
        // Wandering away means there is no critical point under the pair.
        if (!(std::fabs(x - re) <= window)) return false;
    }
}

// The roots of the factor x^2 + b x + c of p, added to roots after polishing on p.
void add_quadratic_factor(const Polynomial& p, double b, double c, Roots& roots) {
    const double half_b = b / 2;
    // One rounding (fused multiply-add): the sign of a tiny discriminant survives, where
    // half_b * half_b - c would round twice.
    const double discriminant = std::fma(half_b, half_b, -c);
    if (discriminant >= 0) {
        // The root of larger magnitude first, the other from the product: no cancellation.
        const double big = -(half_b + std::copysign(std::sqrt(discriminant), half_b));
        const double small = big != 0 ? c / big : 0;
        add_root(roots, polish(p, big));
        add_root(roots, polish(p, small));
        return;
    }
    double root = 0;
    if (double_root_near(p, -half_b, std::sqrt(-discriminant), root)) {
        add_root(roots, root);
        add_root(roots, root);
    }
}

// x^3 + a x^2 + b x + c with c != 0.
void add_cubic_roots(const Polynomial& p, Roots& roots) {
    const double a = p.c[2], b = p.c[1], c = p.c[0];
    // x = t - a/3 gives the depressed t^3 + 3 p3 t + 2 half_q.
    const double third = a / 3;
    const double p3 = (b - a * third) / 3;
    const double half_q = (c + third * (2 * third * third - b)) / 2;
    const double discriminant = half_q * half_q + p3 * p3 * p3;
    // The root farthest from the centroid -a/3: it is simple unless all three coincide, so
    // Newton polishes it quadratically and dividing it out leaves any double root whole.
    double t = 0;
    if (discriminant < 0) {
        // Three real roots (p3 < 0): t = 2 s cos(theta) with cos(3 theta) = -half_q / s^3.
        const double s = std::sqrt(-p3);
        const double cos_3theta = std::min(1.0, std::fabs(half_q) / (s * s * s));
        t = -std::copysign(2 * s * trisected_cosine(cos_3theta), half_q);
    } else {
        // Cardano, with the cube root of larger magnitude so that u - p3/u does not cancel.
        const double u =
            -std::copysign(cube_root(std::fabs(half_q) + std::sqrt(discriminant)), half_q);
        t = u != 0 ? u - p3 / u : 0;
    }
    const double r = polish(p, t - third);
    add_root(roots, r);

    // Divide out x - r, leaving x^2 + q1 x + q0. q0 = -c / r keeps its relative accuracy
    // however small it is. q1 from the top (a + r) is stable unless r is the largest root,
    // when it cancels and the value from the middle ((q0 - b) / r) is stable instead: take
    // whichever reproduces the coefficient it was not made from more closely.
    double q1 = a, q0 = b;
    if (r != 0) {
        q0 = -c / r;
        const double q1_from_top = a + r;
        const double q1_from_middle = (q0 - b) / r;
        const double miss_top = relative(q0 - r * q1_from_top - b,
                                         std::fabs(q0) + std::fabs(r * q1_from_top) + std::fabs(b));
        const double miss_middle = relative(
            q1_from_middle - r - a, std::fabs(q1_from_middle) + std::fabs(r) + std::fabs(a));
        q1 = miss_middle < miss_top ? q1_from_middle : q1_from_top;
    }
    add_quadratic_factor(p, q1, q0, roots);
}

void add_roots(Polynomial p, Roots& roots);

// The factors x^2 + alpha1 x + beta1 and x^2 + alpha2 x + beta2 of a quartic.
struct QuadraticFactors {
    double alpha1, beta1, alpha2, beta2;
};

// How far the product of the factors is from x^4 + a x^3 + b x^2 + c x + d, each
// coefficient's miss relative to the size of its terms (a backward error, in units of 1).
// miss receives the four misses, for Newton's method.
double factor_error(const QuadraticFactors& f, const double (&coefficient)[4], double (&miss)[4]) {
    const auto [a1, b1, a2, b2] = f;
    miss[0] = a1 + a2 - coefficient[0];
    miss[1] = b1 + a1 * a2 + b2 - coefficient[1];
    miss[2] = a1 * b2 + a2 * b1 - coefficient[2];
    miss[3] = b1 * b2 - coefficient[3];
    return relative(miss[0], std::fabs(a1) + std::fabs(a2) + std::fabs(coefficient[0])) +
           relative(miss[1], std::fabs(b1) + std::fabs(a1 * a2) + std::fabs(b2) +
                                 std::fabs(coefficient[1])) +
           relative(miss[2], std::fabs(a1 * b2) + std::fabs(a2 * b1) + std::fabs(coefficient[2])) +
           relative(miss[3], std::fabs(b1 * b2) + std::fabs(coefficient[3]));
}

// Solves the 4x4 system m x = rhs by Gaussian elimination with partial pivoting; false when
// it is singular (the factors share a root).
bool solve4(double (&m)[4][4], double (&rhs)[4]) {
    for (int col = 0; col < 4; ++col) {
        int pivot = col;
        for (int row = col + 1; row < 4; ++row)
            if (std::fabs(m[row][col]) > std::fabs(m[pivot][col])) pivot = row;
        if (m[pivot][col] == 0) return false;
        if (pivot != col) {
            std::swap(m[pivot], m[col]);
            std::swap(rhs[pivot], rhs[col]);
        }
        for (int row = col + 1; row < 4; ++row) {
            const double f = m[row][col] / m[col][col];
            for (int k = col; k < 4; ++k) m[row][k] -= f * m[col][k];
            rhs[row] -= f * rhs[col];
        }
    }
    for (int row = 3; row >= 0; --row) {
        double sum = rhs[row];
        for (int k = row + 1; k < 4; ++k) sum -= m[row][k] * rhs[k];
        rhs[row] = sum / m[row][row];
    }
    return std::isfinite(rhs[0]) && std::isfinite(rhs[1]) && std::isfinite(rhs[2]) &&
           std::isfinite(rhs[3]);
}

// Newton's method on the four equations that say the factors multiply to the quartic. Each
// step is kept only if it shrinks the backward error.
QuadraticFactors refine(QuadraticFactors f, const double (&coefficient)[4]) {
    double miss[4];
    double error = factor_error(f, coefficient, miss);
    for (int step = 0; step < kMaxFactorSteps && error > 0; ++step) {
        const auto [a1, b1, a2, b2] = f;
        // d(miss) / d(alpha1, beta1, alpha2, beta2).
        double jacobian[4][4] = {{1, 0, 1, 0}, {a2, 1, a1, 1}, {b2, a2, b1, a1}, {0, b2, 0, b1}};
        double delta[4] = {-miss[0], -miss[1], -miss[2], -miss[3]};
        if (!solve4(jacobian, delta)) break;
        const QuadraticFactors next{a1 + delta[0], b1 + delta[1], a2 + delta[2], b2 + delta[3]};
        double next_miss[4];
        const double next_error = factor_error(next, coefficient, next_miss);
        if (!(next_error < error)) break;
        f = next;
        error = next_error;
        std::copy(std::begin(next_miss), std::end(next_miss), std::begin(miss));
    }
    return f;
}

// x^4 + a x^3 + b x^2 + c x + d with d != 0.
void add_quartic_roots(const Polynomial& p, Roots& roots) {
    const double a = p.c[3], b = p.c[2], c = p.c[1], d = p.c[0];
    // Ferrari: the quartic is (x^2 + alpha1 x + beta1)(x^2 + alpha2 x + beta2) with
    // u = beta1 + beta2 a root of the resolvent cubic. Its largest real root always gives
    // real factors (it pairs the roots as {r1, r2}, {r3, r4} when all four are real).
    Polynomial resolvent;
    resolvent.degree = 3;
    resolvent.c[3] = 1;
    resolvent.c[2] = -b;
    resolvent.c[1] = a * c - 4 * d;
    resolvent.c[0] = 4 * b * d - a * a * d - c * c;
    Roots resolvent_roots;
    add_roots(resolvent, resolvent_roots);
    if (resolvent_roots.count == 0) return;  // only for non-finite input
    const double u = *std::max_element(resolvent_roots.begin(), resolvent_roots.end());

    // alpha1,2 = (a +- A) / 2 and beta1,2 = (u -+ B) / 2 with A^2 = a^2 - 4(b - u),
    // B^2 = u^2 - 4d and A B = 2c - a u. The larger square root is the more accurate one;
    // the other follows from the product, which also fixes their relative sign.
    const double a_squared = a * a - 4 * (b - u);
    const double b_squared = u * u - 4 * d;
    const double product = 2 * c - a * u;
    double big_a = 0, big_b = 0;
    if (a_squared >= b_squared) {
        big_a = std::sqrt(std::max(0.0, a_squared));
        big_b = big_a > 0 ? product / big_a : 0;
    } else {
        big_b = std::sqrt(std::max(0.0, b_squared));
        big_a = big_b > 0 ? product / big_b : 0;
    }
    QuadraticFactors f{(a + big_a) / 2, (u - big_b) / 2, (a - big_a) / 2, (u + big_b) / 2};
    // The smaller beta from the product beta1 beta2 = d, without cancellation.
    if (std::fabs(f.beta1) < std::fabs(f.beta2)) {
        if (f.beta2 != 0) f.beta1 = d / f.beta2;
    } else if (f.beta1 != 0) {
        f.beta2 = d / f.beta1;
    }
    f = refine(f, {a, b, c, d});
    add_quadratic_factor(p, f.alpha1, f.beta1, roots);
    add_quadratic_factor(p, f.alpha2, f.beta2, roots);
}

// Adds the roots of p, whose leading coefficient is not negligible.
void add_roots(Polynomial p, Roots& roots) {
    // Zero roots exactly, so that the closed forms below may divide by the constant term.
    while (p.degree > 0 && p.c[0] == 0) {
        add_root(roots, 0);
        for (int i = 0; i < p.degree; ++i) p.c[i] = p.c[i + 1];
        p.c[p.degree--] = 0;
    }
    if (p.degree == 0) return;
    const double leading = p.c[p.degree];
    for (int i = 0; i < p.degree; ++i) p.c[i] /= leading;
    p.c[p.degree] = 1;
    switch (p.degree) {
        case 1:
            add_root(roots, -p.c[0]);
            break;
        case 2:
            add_quadratic_factor(p, p.c[1], p.c[0], roots);
            break;
        case 3:
            add_cubic_roots(p, roots);
            break;
        default:
            add_quartic_roots(p, roots);
            break;
    }
}

}  // namespace

Roots solve_polynomial(std::span<const double> coefficients) {
    Roots roots;
    if (coefficients.empty() || coefficients.size() > 5) return roots;
    Polynomial p;
    p.degree = static_cast<int>(coefficients.size()) - 1;
    std::copy(coefficients.begin(), coefficients.end(), p.c);

    // Drop a leading term that cannot matter: if |c_n| B^(n-m) <= eps |c_m|, where c_m is
    // the next non-zero coefficient and B bounds the roots of the rest (Cauchy's bound),
    // then c_n x^n is below the rounding of c_m x^m at every one of those roots.
    while (p.degree > 0) {
        if (p.c[p.degree] == 0) {
            --p.degree;
            continue;
        }
        int next = p.degree - 1;
        while (next >= 0 && p.c[next] == 0) --next;
        if (next < 0) break;  // c_n x^n: a root at zero, n times
        double bound = 1;
        for (int i = 0; i < next; ++i) bound = std::max(bound, 1 + std::fabs(p.c[i] / p.c[next]));
        double leading_term = std::fabs(p.c[p.degree]);
        for (int i = next; i < p.degree; ++i) leading_term *= bound;
        if (!(leading_term <= kEpsilon * std::fabs(p.c[next]))) break;
        for (int i = next + 1; i <= p.degree; ++i) p.c[i] = 0;
        p.degree = next;
    }

    add_roots(p, roots);
    // Insertion sort: at most four values.
    for (std::size_t i = 1; i < static_cast<std::size_t>(roots.count); ++i)
        for (std::size_t j = i; j > 0 && roots.values[j] < roots.values[j - 1]; --j)
            std::swap(roots.values[j], roots.values[j - 1]);
    return roots;
}

Roots solve_quadratic(double a, double b, double c) {
    const double coefficients[] = {c, b, a};
    return solve_polynomial(coefficients);
}

Roots solve_cubic(double a, double b, double c, double d) {
    const double coefficients[] = {d, c, b, a};
    return solve_polynomial(coefficients);
}

Roots solve_quartic(double a, double b, double c, double d, double e) {
    const double coefficients[] = {e, d, c, b, a};
    return solve_polynomial(coefficients);
}

}  // namespace rt
