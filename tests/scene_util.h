// Helpers for tests that build scenes and shapes from scene-format text.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <string>

#include "check.h"
#include "rt/error.h"
#include "rt/options.h"
#include "rt/raster.h"
#include "rt/reader.h"

namespace rt_test {

// A minimal viewer, so that scene text in tests can be just the objects under test.
inline const char* const kTestViewer = "102  0 0 5  0 0 0  1 0 0  0 1 0  4 4\n";

// Whether two rasters hold the same values to the bit (NaN payloads and -0 included).
inline bool identical(const rt::Raster& a, const rt::Raster& b) {
    if (a.width() != b.width() || a.height() != b.height()) return false;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            for (std::size_t i = 0; i < rt::kSpectrumComponents; ++i)
                if (std::bit_cast<std::uint64_t>(a.at(x, y)[i]) !=
                    std::bit_cast<std::uint64_t>(b.at(x, y)[i]))
                    return false;
    return true;
}

inline rt::Scene parse_scene(const std::string& text) {
    std::istringstream in(text);
    return rt::read_scene(in, "test.in");
}

// Scene text for an ID and its numbers, each written with full precision.
// Options that trace every ray down to a depth where what is left is below rounding.
inline rt::RenderOptions exhaustive() {
    rt::RenderOptions options;
    options.min_weight = 0;
    options.max_depth = 60;
    return options;
}

inline std::string object_text(int id, std::initializer_list<double> numbers) {
    std::ostringstream text;
    text.precision(17);
    text << id;
    for (double n : numbers) text << ' ' << n;
    return text.str();
}

// Reads one primitive (ID and numbers, no surface) from text such as "1  2  0 0 0".
inline rt::Shape parse_shape(const std::string& text) {
    std::istringstream in(text);
    rt::SceneReader reader(in, "test.in", {});
    return reader.shape("primitive");
}

// The message of the error that reading `text` as a scene raises, or "" if it reads fine.
inline std::string scene_error(const std::string& text) {
    try {
        parse_scene(text);
    } catch (const rt::Error& e) {
        return e.what();
    }
    return "";
}

// An orthonormal frame whose third axis is along `axis`, for closed forms worked out in
// a primitive's own coordinates.
struct Frame {
    rt::Vec3 e1, e2, e3;  // e3 is the unit axis
    rt::Vec3 local(const rt::Vec3& v) const { return {dot(v, e1), dot(v, e2), dot(v, e3)}; }
    rt::Vec3 world(const rt::Vec3& v) const { return v.x * e1 + v.y * e2 + v.z * e3; }
};

inline Frame frame_around(const rt::Vec3& axis) {
    const rt::Vec3 e3 = normalized(axis);
    const rt::Vec3 helper = std::fabs(e3.x) < 0.5 ? rt::Vec3(1, 0, 0) : rt::Vec3(0, 1, 0);
    const rt::Vec3 e1 = normalized(cross(e3, helper));
    return {e1, cross(e3, e1), e3};
}

// The distance along a ray to a sphere, solved geometrically rather than as the quadratic
// the primitives use: the nearest root beyond 1e-9, or nothing.
inline std::optional<double> sphere_distance(const rt::Vec3& centre, double r, const rt::Ray& ray) {
    const rt::Vec3 to_centre = centre - ray.origin;
    const double along = dot(to_centre, ray.direction);
    // Measured across the ray, without the cancellation of |c − o|² − along².
    const double miss2 = length_squared(to_centre - along * ray.direction);
    if (miss2 > r * r) return std::nullopt;
    const double half = std::sqrt(r * r - miss2);
    if (along - half > 1e-9) return along - half;
    if (along + half > 1e-9) return along + half;
    return std::nullopt;
}

// The nearest hit beyond a small tolerance, or nothing.
inline std::optional<rt::Hit> first_hit(const rt::Shape& shape, const rt::Ray& ray,
                                        double t_max = rt::kInfinity) {
    rt::Hit hit;
    if (!shape.intersect(ray, {1e-9, t_max}, hit)) return std::nullopt;
    return hit;
}

}  // namespace rt_test
