// Real roots of polynomials of degree at most 4: the original's "code for solving polynomials
// of degree less than 5", used by the torus.
//
// The roots come from the closed forms (a stable quadratic, Cardano's or the trigonometric
// cubic, Ferrari's quartic through its resolvent cubic), refined and then polished by Newton's
// method on the polynomial itself, so each simple root is about as accurate as the
// polynomial's own rounding allows: within a few units of eps times its condition number
// (sum |c_i x^i| / |x p'(x)|), which is a few eps for well-separated roots, even when the
// roots span many orders of magnitude. A root of multiplicity m is sensitive to rounding as
// eps^(1/m): a double root comes back within about 1e-8 of its size, a quadruple within 1e-4.
#pragma once

#include <array>
#include <cstddef>
#include <span>

namespace rt {

// The real roots in ascending order, each repeated root listed once per multiplicity (a
// double root appears twice). A complex pair whose imaginary part is below the rounding
// error of the polynomial counts as a double real root, so tangencies are never lost.
// Fixed capacity: solving allocates nothing.
struct Roots {
    static constexpr int kCapacity = 4;
    std::array<double, kCapacity> values{};
    int count = 0;

    double operator[](int i) const { return values[static_cast<std::size_t>(i)]; }
    const double* begin() const { return values.data(); }
    const double* end() const { return values.data() + count; }
};

// coefficients[i] multiplies x^i, so {c0, c1, c2} is c2 x^2 + c1 x + c0; at most 5 of them
// (more return no roots). A leading coefficient so small that its term cannot change the
// other roots by more than rounding is dropped, and the degree falls; the roots it would
// have added lie beyond about 1/eps^(1/k) times the others (k the drop in degree). The zero
// polynomial and non-zero constants have no roots.
Roots solve_polynomial(std::span<const double> coefficients);

// The same, with the coefficients written highest power first: a x^2 + b x + c = 0, ...
Roots solve_quadratic(double a, double b, double c);
Roots solve_cubic(double a, double b, double c, double d);
Roots solve_quartic(double a, double b, double c, double d, double e);

}  // namespace rt
