// The table of object kinds: each keyword of the language, the contract ID it writes, and its
// fields in the contract's order with their types, defaults and how each is written. The
// evaluator checks fields against it as they are set; the emitter writes each kind's numbers
// from its row alone, so a new kind is one row here.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "rt/vec.h"

namespace rtpp {

enum class Category { primitive, csg, group, surface, light, ambient, background, camera, viewer };

enum class FieldType {
    number,
    flag,  // a number read as true (non-zero) or false
    vector,
    colour,   // a vector, or one number for all three components
    surface,  // a surface object
    string,
    size,  // two whole numbers: width, height
};

// How the emitter writes a field, where the field stands in the contract's order.
enum class Write {
    number,   // its number
    vector,   // its three numbers (a colour's too)
    surface,  // the surface, in full
    slot,     // a primitive's surface: in full, or 106 for the default surface
    file,     // the file name, quoted, relative to where rtpp runs
    size,     // width and height
    // Exactly one of this field and `other`: this one's number, or the cosine of the other,
    // which is in degrees.
    cosine_or_degrees,
    three,    // repeated vertices, exactly three
    counted,  // repeated vertices, three or more: their count, then each
    // A mesh: the counts of this repeated vector and of `other`, this one's vectors, then
    // the other's, checked as index triples into this one.
    indexed,
    // A smooth mesh: as indexed, with each vertex followed by the repeated `normal` vector of
    // the same place (as many normals as vertices).
    indexed_normals,
    // Nothing where it stands: the other of a pair, or a flag that chooses the ID (`id`
    // when true). A camera's fields are all read together (Emitter::camera).
    none,
};

struct FieldSpec {
    const char* name;
    FieldType type;
    bool has_default = false;
    double default_number = 0;
    rt::Vec3 default_vector;
    bool repeated = false;  // each statement adds one (a polygon's vertices)
    Write write = Write::none;
    const char* other = nullptr;  // the field written with this one (Write above)
    int id = 0;                   // a flag's: the ID the kind writes when it is true
};

struct Kind {
    const char* keyword;
    int id;  // the contract's ID; for kinds that write more than one, the usual one
    Category category;
    std::vector<FieldSpec> fields;  // in the contract's order
    // How messages list the fields, where not in that order ("normal, distance, surface").
    const char* listed = nullptr;
    // A composite of more than two: the ID that joins the operands after the first (a
    // difference takes their union).
    int rest_id = 0;

    const FieldSpec* field(std::string_view name) const;
    std::string field_names() const;  // "radius, centre, surface"
    bool takes_surface() const { return field("surface") != nullptr; }
};

const Kind* find_kind(std::string_view keyword);
const std::vector<Kind>& all_kinds();

// Transforms every placeable kind accepts, applied in order.
bool is_transform(std::string_view field);

}  // namespace rtpp
