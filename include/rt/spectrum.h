// Light and colour as a fixed number of spectral components (red, green, blue).
#pragma once

#include <array>
#include <cstddef>

namespace rt {

// The original made the number of components a compile-time constant "for the sake of
// future expansion"; so do we.
template <std::size_t N>
struct BasicSpectrum {
    static constexpr std::size_t kComponents = N;
    std::array<double, N> c{};

    constexpr BasicSpectrum() = default;
    constexpr explicit BasicSpectrum(double all) { c.fill(all); }
    template <typename... T>
    requires(sizeof...(T) == N && N > 1) constexpr BasicSpectrum(T... values)
        : c{static_cast<double>(values)...} {}

    constexpr double& operator[](std::size_t i) { return c[i]; }
    constexpr double operator[](std::size_t i) const { return c[i]; }

    constexpr BasicSpectrum& operator+=(const BasicSpectrum& o) {
        for (std::size_t i = 0; i < N; ++i) c[i] += o.c[i];
        return *this;
    }
    constexpr BasicSpectrum& operator*=(const BasicSpectrum& o) {
        for (std::size_t i = 0; i < N; ++i) c[i] *= o.c[i];
        return *this;
    }
    constexpr BasicSpectrum& operator*=(double s) {
        for (double& v : c) v *= s;
        return *this;
    }
    constexpr bool operator==(const BasicSpectrum&) const = default;

    constexpr bool is_black() const {
        for (double v : c)
            if (v != 0) return false;
        return true;
    }
};

template <std::size_t N>
constexpr BasicSpectrum<N> operator+(BasicSpectrum<N> a, const BasicSpectrum<N>& b) {
    return a += b;
}
template <std::size_t N>
constexpr BasicSpectrum<N> operator*(BasicSpectrum<N> a, const BasicSpectrum<N>& b) {
    return a *= b;
}
template <std::size_t N>
constexpr BasicSpectrum<N> operator*(BasicSpectrum<N> a, double s) {
    return a *= s;
}
template <std::size_t N>
constexpr BasicSpectrum<N> operator*(double s, BasicSpectrum<N> a) {
    return a *= s;
}

inline constexpr std::size_t kSpectrumComponents = 3;
using Spectrum = BasicSpectrum<kSpectrumComponents>;

}  // namespace rt
