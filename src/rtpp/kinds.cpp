#include "rtpp/kinds.h"

namespace rtpp {

namespace {

FieldSpec required(const char* name, FieldType type) { return {name, type, false, 0, {}, false}; }
FieldSpec optional(const char* name, FieldType type) { return {name, type, false, 0, {}, false}; }
FieldSpec with_default(const char* name, double value) {
    return {name, FieldType::number, true, value, {}, false};
}
FieldSpec with_default(const char* name, FieldType type, rt::Vec3 value) {
    return {name, type, true, 0, value, false};
}
FieldSpec list(const char* name) { return {name, FieldType::vector, false, 0, {}, true}; }

// Required and optional fields look alike in the table; the emitter asks for each as it
// writes it, and a missing field without a default is an error there. Fields that have an
// alternative (a cone's alpha or angle) are optional here and checked by the emitter.
std::vector<Kind> make_kinds() {
    using T = FieldType;
    const rt::Vec3 origin{0, 0, 0};
    const FieldSpec surface = optional("surface", T::surface);
    return {
        {"sphere",
         1,
         Category::primitive,
         {required("radius", T::number), with_default("centre", T::vector, origin), surface}},
        {"plane",
         2,
         Category::primitive,
         {required("normal", T::vector), with_default("distance", 0), surface}},
        {"disk",
         3,
         Category::primitive,
         {with_default("centre", T::vector, origin), required("normal", T::vector),
          required("radius", T::number), surface}},
        {"annulus",
         4,
         Category::primitive,
         {with_default("centre", T::vector, origin), required("normal", T::vector),
          required("outer", T::number), with_default("inner", 0), surface}},
        {"triangle", 5, Category::primitive, {list("vertex"), surface}},
        {"parallelogram",
         6,
         Category::primitive,
         {with_default("corner", T::vector, origin), required("a", T::vector),
          required("b", T::vector), surface}},
        {"cone",
         8,
         Category::primitive,
         {optional("alpha", T::number), optional("angle", T::number), with_default("start", 0),
          with_default("finish", 1), with_default("apex", T::vector, origin),
          required("axis", T::vector), surface}},
        {"cylinder",
         9,
         Category::primitive,
         {required("radius", T::number), with_default("start", 0), with_default("finish", 1),
          with_default("origin", T::vector, origin), required("axis", T::vector), surface}},
        {"torus",
         10,
         Category::primitive,
         {with_default("centre", T::vector, origin), required("axis", T::vector),
          required("major", T::number), required("minor", T::number), surface}},
        {"polygon", 11, Category::primitive, {list("vertex"), surface}},
        {"box",
         12,
         Category::primitive,
         {required("min", T::vector), required("max", T::vector), surface}},
        {"quadric",
         13,
         Category::primitive,
         {with_default("xx", 0), with_default("yy", 0), with_default("zz", 0),
          with_default("xy", 0), with_default("xz", 0), with_default("yz", 0), with_default("x", 0),
          with_default("y", 0), with_default("z", 0), with_default("constant", 0),
          required("min", T::vector), required("max", T::vector), surface}},
        {"mesh", 14, Category::primitive, {list("vertex"), list("triangle"), surface}},
        {"union", 20, Category::csg, {}},
        {"intersection", 21, Category::csg, {}},
        {"difference", 22, Category::csg, {}},
        {"group", 0, Category::group, {}},
        {"surface",
         100,
         Category::surface,
         {required("colour", T::colour), with_default("ks", 0), with_default("ke", 1),
          required("kd", T::number), with_default("kt", 0), with_default("ior", 1)}},
        {"checker",
         107,
         Category::surface,
         {required("cell", T::number), required("a", T::surface), required("b", T::surface)}},
        {"image",
         108,
         Category::surface,
         {with_default("origin", T::vector, origin), required("u", T::vector),
          required("v", T::vector), required("file", T::string), required("base", T::surface)}},
        {"glass",
         114,
         Category::surface,
         {with_default("colour", T::colour, {1, 1, 1}), with_default("ks", 0),
          with_default("ke", 1), with_default("kd", 0), required("ior", T::number),
          with_default("absorption", T::colour, origin)}},
        {"point_light",
         104,
         Category::light,
         {required("position", T::vector),
          required("intensity", T::colour),
          {"falloff", T::flag, true, 0, {}, false}}},
        {"ambient", 103, Category::ambient, {required("intensity", T::colour)}},
        {"spot_light",
         109,
         Category::light,
         {required("position", T::vector), required("direction", T::vector),
          optional("cos_cutoff", T::number), optional("cutoff_angle", T::number),
          with_default("exponent", 0), required("intensity", T::colour)}},
        {"sphere_light",
         110,
         Category::light,
         {with_default("samples", 16), with_default("centre", T::vector, origin),
          required("radius", T::number), required("intensity", T::colour)}},
        {"directional_light",
         113,
         Category::light,
         {required("direction", T::vector), required("intensity", T::colour)}},
        {"camera",
         102,
         Category::camera,
         {required("position", T::vector),
          required("look_at", T::vector),
          with_default("up", T::vector, {0, 1, 0}),
          optional("fov", T::number),
          optional("half_width", T::number),
          required("size", T::size),
          {"upright", T::flag, true, 0, {}, false}}},
        {"viewer",
         102,
         Category::viewer,
         {required("eye", T::vector), required("look_at", T::vector), required("x", T::vector),
          required("y", T::vector), required("size", T::size)}},
    };
}

}  // namespace

const std::vector<Kind>& all_kinds() {
    static const std::vector<Kind> kinds = make_kinds();
    return kinds;
}

const Kind* find_kind(std::string_view keyword) {
    for (const Kind& kind : all_kinds())
        if (keyword == kind.keyword) return &kind;
    return nullptr;
}

const FieldSpec* Kind::field(std::string_view name) const {
    for (const FieldSpec& spec : fields)
        if (name == spec.name) return &spec;
    return nullptr;
}

std::string Kind::field_names() const {
    std::string names;
    for (const FieldSpec& spec : fields)
        names += (names.empty() ? "" : ", ") + std::string(spec.name);
    return names;
}

bool is_transform(std::string_view field) {
    return field == "translate" || field == "rotate" || field == "scale" || field == "frame";
}

}  // namespace rtpp
