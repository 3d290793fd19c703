// Helpers for tests that build scenes and shapes from scene-format text.
#pragma once

#include <initializer_list>
#include <optional>
#include <sstream>
#include <string>

#include "check.h"
#include "rt/error.h"
#include "rt/reader.h"

namespace rt_test {

// A minimal viewer, so that scene text in tests can be just the objects under test.
inline const char* const kTestViewer = "102  0 0 5  0 0 0  1 0 0  0 1 0  4 4\n";

inline rt::Scene parse_scene(const std::string& text) {
    std::istringstream in(text);
    return rt::read_scene(in, "test.in");
}

// Scene text for an ID and its numbers, each written with full precision.
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

// The nearest hit beyond a small tolerance, or nothing.
inline std::optional<rt::Hit> first_hit(const rt::Shape& shape, const rt::Ray& ray,
                                        double t_max = rt::kInfinity) {
    rt::Hit hit;
    if (!shape.intersect(ray, {1e-9, t_max}, hit)) return std::nullopt;
    return hit;
}

}  // namespace rt_test
