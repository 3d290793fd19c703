// The table of object kinds: each keyword of the language, the contract ID it writes, and its
// fields with their types and defaults. The evaluator checks fields against it as they are
// set; the emitter writes each kind's numbers in the contract's order.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "rt/vec.h"

namespace rtpp {

enum class Category { primitive, csg, group, surface, light, ambient, camera, viewer };

enum class FieldType {
    number,
    flag,  // a number read as true (non-zero) or false
    vector,
    colour,   // a vector, or one number for all three components
    surface,  // a surface object
    string,
    size,  // two whole numbers: width, height
};

struct FieldSpec {
    const char* name;
    FieldType type;
    bool has_default = false;
    double default_number = 0;
    rt::Vec3 default_vector;
    bool repeated = false;  // each statement adds one (a polygon's vertices)
};

struct Kind {
    const char* keyword;
    int id;  // the contract's ID; for kinds that write more than one, the usual one
    Category category;
    std::vector<FieldSpec> fields;

    const FieldSpec* field(std::string_view name) const;
    std::string field_names() const;  // "radius, centre, surface"
    bool takes_surface() const { return field("surface") != nullptr; }
};

const Kind* find_kind(std::string_view keyword);
const std::vector<Kind>& all_kinds();

// Transforms every placeable kind accepts, applied in order.
bool is_transform(std::string_view field);

}  // namespace rtpp
