#include "rtpp/kinds.h"

namespace rtpp {

namespace {

using T = FieldType;

// Fields without a default are checked by the emitter as it writes them: a missing one is an
// error there, at the object.
FieldSpec number(const char* name) { return {name, T::number, false, 0, {}, false, Write::number}; }
FieldSpec number(const char* name, double fallback) {
    return {name, T::number, true, fallback, {}, false, Write::number};
}
FieldSpec vector(const char* name) { return {name, T::vector, false, 0, {}, false, Write::vector}; }
FieldSpec vector(const char* name, rt::Vec3 fallback) {
    return {name, T::vector, true, 0, fallback, false, Write::vector};
}
FieldSpec colour(const char* name) { return {name, T::colour, false, 0, {}, false, Write::vector}; }
FieldSpec colour(const char* name, rt::Vec3 fallback) {
    return {name, T::colour, true, 0, fallback, false, Write::vector};
}
FieldSpec surface(const char* name) {
    return {name, T::surface, false, 0, {}, false, Write::surface};
}
FieldSpec file(const char* name) { return {name, T::string, false, 0, {}, false, Write::file}; }
FieldSpec size() { return {"size", T::size, false, 0, {}, false, Write::size}; }
// One of a pair: a cosine, or the angle in degrees (`degrees`) whose cosine is written.
FieldSpec cosine(const char* name, const char* degrees) {
    return {name, T::number, false, 0, {}, false, Write::cosine_or_degrees, degrees};
}
// The other of a pair, written by the first (or, for the camera, read with the others).
FieldSpec alternative(const char* name) {
    return {name, T::number, false, 0, {}, false, Write::none};
}
// False unless set; when true, the kind writes `id` instead of its own.
FieldSpec flag(const char* name, int id = 0) {
    return {name, T::flag, true, 0, {}, false, Write::none, nullptr, id};
}
// Each statement adds one vector.
FieldSpec list(const char* name, Write write, const char* other = nullptr) {
    return {name, T::vector, false, 0, {}, true, write, other};
}

// Every primitive takes a surface last: its own, or the default one.
Kind primitive(const char* keyword, int id, std::vector<FieldSpec> fields,
               const char* listed = nullptr) {
    fields.push_back({"surface", T::surface, false, 0, {}, false, Write::slot});
    return {keyword, id, Category::primitive, std::move(fields), listed};
}
Kind kind(const char* keyword, int id, Category category, std::vector<FieldSpec> fields) {
    return {keyword, id, category, std::move(fields)};
}
Kind composite(const char* keyword, int id, int rest_id) {
    return {keyword, id, Category::csg, {}, nullptr, rest_id};
}

// One row per kind, its fields in the order the contract writes them.
std::vector<Kind> make_kinds() {
    const rt::Vec3 origin{0, 0, 0};
    const auto n = [](const char* name) { return number(name, 0); };  // the quadric's terms
    return {
        primitive("sphere", 1, {number("radius"), vector("centre", origin)}),
        // The language gives the normal first, as in normal·x = distance.
        primitive("plane", 2, {number("distance", 0), vector("normal")},
                  "normal, distance, surface"),
        primitive("disk", 3, {vector("centre", origin), vector("normal"), number("radius")}),
        primitive(
            "annulus", 4,
            {vector("centre", origin), vector("normal"), number("outer"), number("inner", 0)}),
        primitive("triangle", 5, {list("vertex", Write::three)}),
        primitive("parallelogram", 6, {vector("corner", origin), vector("a"), vector("b")}),
        primitive("cone", 8,
                  {cosine("alpha", "angle"), alternative("angle"), number("start", 0),
                   number("finish", 1), vector("apex", origin), vector("axis")}),
        primitive("cylinder", 9,
                  {number("radius"), number("start", 0), number("finish", 1),
                   vector("origin", origin), vector("axis")}),
        primitive("torus", 10,
                  {vector("centre", origin), vector("axis"), number("major"), number("minor")}),
        primitive("polygon", 11, {list("vertex", Write::counted)}),
        primitive("box", 12, {vector("min"), vector("max")}),
        primitive("quadric", 13,
                  {n("xx"), n("yy"), n("zz"), n("xy"), n("xz"), n("yz"), n("x"), n("y"), n("z"),
                   n("constant"), vector("min"), vector("max")}),
        primitive("mesh", 14,
                  {list("vertex", Write::indexed, "triangle"), list("triangle", Write::none)}),
        // A number then a path, as the contract has them: `mesh_file { file "bunny.ply" }`.
        primitive("mesh_file", 15, {number("mode", 0), file("file")}),
        primitive("smooth_mesh", 16,
                  {list("vertex", Write::indexed_normals, "triangle"), list("normal", Write::none),
                   list("triangle", Write::none)}),
        composite("union", 20, 20),
        composite("intersection", 21, 21),
        composite("difference", 22, 20),
        kind("group", 0, Category::group, {}),
        kind("surface", 100, Category::surface,
             {colour("colour"), number("ks", 0), number("ke", 1), number("kd"), number("kt", 0),
              number("ior", 1)}),
        kind("checker", 107, Category::surface, {number("cell"), surface("a"), surface("b")}),
        kind("image", 108, Category::surface,
             {vector("origin", origin), vector("u"), vector("v"), file("file"), surface("base")}),
        kind("glass", 114, Category::surface,
             {colour("colour", {1, 1, 1}), number("ks", 0), number("ke", 1), number("kd", 0),
              number("ior"), colour("absorption", origin)}),
        kind("point_light", 104, Category::light,
             {vector("position"), colour("intensity"), flag("falloff", 101)}),
        kind("ambient", 103, Category::ambient, {colour("intensity")}),
        kind("background", 115, Category::background, {colour("colour")}),
        kind("spot_light", 109, Category::light,
             {vector("position"), vector("direction"), cosine("cos_cutoff", "cutoff_angle"),
              alternative("cutoff_angle"), number("exponent", 0), colour("intensity")}),
        kind("sphere_light", 110, Category::light,
             {number("samples", 16), vector("centre", origin), number("radius"),
              colour("intensity")}),
        kind("directional_light", 113, Category::light, {vector("direction"), colour("intensity")}),
        // Its viewer vectors are computed from all its fields together (Emitter::camera).
        kind("camera", 102, Category::camera,
             {vector("position"), vector("look_at"), vector("up", {0, 1, 0}), alternative("fov"),
              alternative("half_width"), size(), flag("upright")}),
        kind("viewer", 102, Category::viewer,
             {vector("eye"), vector("look_at"), vector("x"), vector("y"), size()}),
    };
}

}  // namespace

const std::vector<Kind>& all_kinds() {
    static const std::vector<Kind> kinds = make_kinds();
    return kinds;
}

const Kind* find_kind(std::string_view keyword) {
    // The first letter first: this runs for every let and object statement.
    if (keyword.empty()) return nullptr;
    for (const Kind& kind : all_kinds())
        if (kind.keyword[0] == keyword[0] && keyword == kind.keyword) return &kind;
    return nullptr;
}

const FieldSpec* Kind::field(std::string_view name) const {
    for (const FieldSpec& spec : fields)
        if (name == spec.name) return &spec;
    return nullptr;
}

std::string Kind::field_names() const {
    if (listed != nullptr) return listed;
    std::string names;
    for (const FieldSpec& spec : fields)
        names += (names.empty() ? "" : ", ") + std::string(spec.name);
    return names;
}

bool is_transform(std::string_view field) {
    return field == "translate" || field == "rotate" || field == "scale" || field == "frame";
}

}  // namespace rtpp
