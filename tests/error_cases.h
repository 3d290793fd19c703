// The scene errors of the contract, each with the message rt must give, for the reader's
// unit test and for the command-line test (which also checks the exit status and that the
// output file is left alone). Scenes are read as "test.in".
#pragma once

#include <string>
#include <vector>

#include "scene_util.h"

namespace rt_test {

struct ErrorCase {
    std::string scene;
    std::string message;
};

inline std::vector<ErrorCase> scene_error_cases() {
    const std::string kViewer = kTestViewer;
    const std::string kSurface = " 100 1 1 1 0 1 1 0 1";
    return {
        {kViewer + "42 1 2 3", "test.in:2:1: unknown object ID 42"},
        {kViewer + "1 1 0 0", "test.in:2:8: unexpected end of file: expected sphere centre"},
        {kViewer + "1 1 0 x 0" + kSurface,
         "test.in:2:7: expected sphere centre (a number), got 'x'"},
        {kViewer + "1 1 0 0 inf" + kSurface,
         "test.in:2:9: sphere centre must be a finite number, got 'inf'"},
        {kViewer + "1 1 0 0 nan" + kSurface, "sphere centre must be a finite number, got 'nan'"},
        {kViewer + "1 1 0 0 1e999" + kSurface,
         "sphere centre must be a finite number, got '1e999'"},
        {kViewer + "1.5 1 0 0 0" + kSurface,
         "test.in:2:1: object ID must be a whole number, got 1.5"},
        {kViewer + "100 1 1 1 0 1 1 0 1",
         "test.in:2:1: surface 100 (simple surface) found where an object is expected"},
        {kViewer + "106",
         "test.in:2:1: surface 106 (use default surface) found where an object is expected"},
        {"103 1 1 1", "test.in:1:10: no viewer (102) in the scene"},
        {"", "test.in:1:1: the scene is empty: the file holds no objects"},
        {kViewer + kViewer, "test.in:2:1: a second viewer (102); a scene has exactly one"},
        {"102 0 0 5 0 0 0 1 0 0 0 1 0 0 4",
         "test.in:1:29: viewer x resolution must be between 1 and 16384, got 0"},
        {"102 0 0 5 0 0 0 1 0 0 0 1 0 4 -3",
         "test.in:1:31: viewer y resolution must be between 1 and 16384, got -3"},
        {"102 0 0 5 0 0 0 1 0 0 0 1 0 16385 4",
         "viewer x resolution must be between 1 and 16384, got 16385"},
        {"102 0 0 5 0 0 0 1 0 0 0 1 0 16384 16384",
         "test.in:1:29: viewer resolution 16384x16384 exceeds the limit of 67108864 pixels"},
        {"102 0 0 5 0 0 0 1 0 0 0 1 0 4.5 4",
         "viewer x resolution must be a whole number, got 4.5"},
        {"102 0 0 5 0 0 5 1 0 0 0 1 0 4 4",
         "test.in:1:11: viewer look-at point must differ from the eye position"},
        {"102 0 0 5 0 0 0 0 0 0 0 1 0 4 4",
         "test.in:1:17: viewer x vector must have a non-zero, finite length"},
        {kViewer + "2 0 0 0 0" + kSurface,
         "test.in:2:5: plane normal must have a non-zero length"},
        {kViewer + "1 1 0 0 0 106",
         "test.in:2:11: 106 (use default surface) but no default surface has been set with 105"},
        {kViewer + "1 1 0 0 0 101 1 1 1 1 1 1",
         "test.in:2:11: expected a surface ID (one of 100, 106, 107, 108, 111, 114), got 101 "
         "(point "
         "light)"},
        {kViewer + "1 1 0 0 0 100 1 1 -1 0 1 1 0 1",
         "test.in:2:15: surface colour components must be >= 0"},
        {kViewer + "1 1 0 0 0 100 1 1 1 0 1 1 0.5 0",
         "test.in:2:31: surface ior must be > 0 when kt > 0, got 0"},
        {kViewer + "1 1 0 0 0 100 1 1 1 -0.5 1 1 0 1",
         "test.in:2:21: surface ks (specular coefficient) must be >= 0, got -0.5"},
        {kViewer + "\"quoted\"", "test.in:2:1: expected object ID (a number), got a quoted string"},
        {kViewer + "\"unterminated", "test.in:2:1: unterminated quoted path"},
        {kViewer + std::string(5000, '1'), "test.in:2:1: token longer than 4096 characters"},
        // The mesh (14): counts, vertices and indices, each at its own place.
        {kViewer + "14 4 2  0 0 0  1 0 0  0 1 0  0 0 1  0 1 2  0 1 4" + kSurface,
         "test.in:2:48: mesh triangle 1 vertex index must be in [0, 4), got 4"},
        {kViewer + "14 4 1  0 0 0  1 0 0  0 1 0  0 0 1  0 -1 2" + kSurface,
         "test.in:2:39: mesh triangle 0 vertex index must be in [0, 4), got -1"},
        {kViewer + "14 3 1\n0 0 0\n1 0 0\n0 1 0\n0 1 12345678901" + kSurface,
         "test.in:6:5: mesh triangle 0 vertex index must be in [0, 3), got 12345678901"},
        {kViewer + "14 4 1  0 0 0  1 0 0  0 1 0  0 0 1  1.5 1 2" + kSurface,
         "test.in:2:37: mesh triangle 0 vertex index must be a whole number, got 1.5"},
        {kViewer + "14 2 1  0 0 0  1 0 0  0 1 1" + kSurface,
         "test.in:2:4: mesh vertex count must be between 3 and 2147483647, got 2"},
        {kViewer + "14 3 0  0 0 0  1 0 0  0 1 0" + kSurface,
         "test.in:2:6: mesh triangle count must be between 1 and 2147483647, got 0"},
        {kViewer + "14 3 2  0 0 0  1 0 0  0 1 0  0 1 2",
         "test.in:2:35: unexpected end of file: expected mesh triangle 1 vertex index"},
        {kViewer + "14 3 2  0 0 0  1 0 0  2 0 0  0 1 2  0 0 1" + kSurface,
         "test.in:2:6: mesh has no triangle with non-zero area (all 2 are degenerate)"},
        {kViewer + "14 3 1  0 0 0  1 0 0  0 2e100 0  0 1 2" + kSurface,
         "test.in:2:23: mesh vertex 2 coordinates must be at most 1e+100 in absolute value"},
        {kViewer + "14 3 1  0 0 0  1 x 0  0 1 0  0 1 2" + kSurface,
         "test.in:2:18: expected mesh vertex 1 (a number), got 'x'"},
    };
}

}  // namespace rt_test
