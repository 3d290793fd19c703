#include "rtpp/emitter.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "rtpp/camera.h"

namespace rtpp {

namespace {

// Reads fields by name, with the kind's defaults, failing at the object for a missing one.
class Fields {
  public:
    explicit Fields(const ObjectValue& object) : object_(object) {}

    const FieldValue* find(const char* name) const { return object_.find(name); }
    bool has(const char* name) const { return find(name) != nullptr; }
    SourcePos pos_of(const char* name) const {
        const FieldValue* f = find(name);
        return f ? f->pos : object_.pos;
    }
    double number(const char* name) const {
        if (const FieldValue* f = find(name)) return f->value.number;
        return spec(name).default_number;
    }
    rt::Vec3 vector(const char* name) const {
        if (const FieldValue* f = find(name)) return f->value.vector;
        return spec(name).default_vector;
    }
    const Value& value(const char* name) const {
        if (const FieldValue* f = find(name)) return f->value;
        missing(name);
    }
    // The values of a repeated field, in order.
    std::vector<const FieldValue*> all(const char* name) const {
        std::vector<const FieldValue*> found;
        for (const FieldValue& f : object_.fields)
            if (std::string_view(f.spec->name) == name) found.push_back(&f);
        return found;
    }
    // The values of a repeated field of vertices, which must number from min to max.
    std::vector<const FieldValue*> count(const char* name, std::size_t min, std::size_t max) const {
        const auto list = all(name);
        if (list.size() < min || list.size() > max)
            fail(object_.pos,
                 std::string(object_.kind->keyword) + " needs " +
                     (min == max ? std::to_string(min) : "at least " + std::to_string(min)) +
                     " vertices, got " + std::to_string(list.size()));
        return list;
    }
    // Exactly one of two alternative fields.
    const char* one_of(const char* a, const char* b) const {
        if (has(a) && has(b))
            fail(pos_of(b),
                 std::string(object_.kind->keyword) + " takes " + a + " or " + b + ", not both");
        if (has(a)) return a;
        if (has(b)) return b;
        fail(object_.pos,
             std::string(object_.kind->keyword) + ": missing field '" + a + "' (or '" + b + "')");
    }
    [[noreturn]] void missing(const char* name) const {
        fail(object_.pos, std::string(object_.kind->keyword) + ": missing field '" + name + "'");
    }

  private:
    const FieldSpec& spec(const char* name) const {
        const FieldSpec* s = object_.kind->field(name);
        if (s == nullptr || !s->has_default) missing(name);
        return *s;
    }
    const ObjectValue& object_;
};

}  // namespace

Emitter::Emitter(const SourceFiles& files, const Limits& limits, std::string& out)
    : files_(files), limits_(limits), out_(out) {}

// Each top-level object starts a line; a marker comes first unless the line already follows
// the source (the next source line after the previous object's).
void Emitter::start_line(SourcePos pos) {
    if (line_open_) {
        out_ += '\n';
        ++mapped_line_;
        line_open_ = false;
    }
    mark(pos);
}

// Inside an object, a part written on another source line (a CSG operand) gets its own line.
// Each object's start is where the output's size is checked: one object is bounded by the
// list limit, and the scene, held until the end, by Limits::output_size.
void Emitter::mark(SourcePos pos) {
    if (out_.size() > limits_.output_size)
        fail(pos,
             "the scene written is larger than " + std::to_string(limits_.output_size) + " bytes");
    if (line_open_ && pos.file == mapped_file_ && pos.line == mapped_line_) return;
    if (line_open_) {
        out_ += '\n';
        ++mapped_line_;
        line_open_ = false;
    }
    if (pos.file != mapped_file_ || pos.line != mapped_line_) {
        const std::string& name = files_[pos.file].name;
        // A name a marker cannot quote gets no marker: rt then names the generated line.
        if (name.find_first_of("\"\n") == std::string::npos) {
            out_ += "#line " + std::to_string(pos.line) + " \"" + name + "\"\n";
            mapped_file_ = pos.file;
            mapped_line_ = pos.line;
        }
    }
    line_open_ = true;
}

void Emitter::word(std::string_view text) {
    if (!out_.empty() && out_.back() != '\n') out_ += ' ';
    out_ += text;
}

// The shortest text that reads back as the same double, so a value written in the source
// reaches rt unchanged (and -0 as 0, as people write it).
void Emitter::number(double value) {
    if (value == 0) value = 0;
    char text[32];
    const auto [end, error] = std::to_chars(text, text + sizeof text, value);
    word(std::string_view(text, static_cast<std::size_t>(end - text)));
}

void Emitter::vector(const rt::Vec3& v) {
    number(v.x);
    number(v.y);
    number(v.z);
}

void Emitter::frame(int id, const Frame& f) {
    number(id);
    vector(f.origin);
    vector(f.x);
    vector(f.y);
    vector(f.z);
}

// Every object written counts, a composite's operands and a group's members included, and
// the whole is refused before any of it is written.
void Emitter::place(const ObjectValue& object) {
    if (object.parts > limits_.objects - objects_)
        fail(object.pos, "more than " + std::to_string(limits_.objects) + " objects written");
    objects_ += object.parts;
    place_in(object, Frame{});
}

void Emitter::place_in(const ObjectValue& object, const Frame& parent) {
    const Frame placed = compose(parent, object.transform);
    const Category category = object.kind->category;
    if (category == Category::group) {
        for (const ObjectPtr& child : object.children) place_in(*child, placed);
        return;
    }
    switch (category) {
        case Category::primitive:
        case Category::csg:
            start_line(object.pos);
            shape(object, placed);
            return;
        case Category::light:
            start_line(object.pos);
            if (!placed.is_identity()) frame(112, placed);
            numbers(object);
            return;
        case Category::ambient:
            if (!placed.is_identity()) fail(object.pos, "an ambient light cannot be transformed");
            start_line(object.pos);
            numbers(object);
            return;
        case Category::background:
            // Caught here rather than by rt, so that the message names both places in the
            // source, not in the numbers written.
            if (!placed.is_identity()) fail(object.pos, "a background cannot be transformed");
            if (background_)
                fail(object.pos, "a second background; a scene has at most one, the first is at " +
                                     files_.place(*background_));
            background_ = object.pos;
            start_line(object.pos);
            numbers(object);
            return;
        case Category::camera:
        case Category::viewer:
            if (!placed.is_identity()) fail(object.pos, "a camera cannot be transformed");
            if (have_camera_) fail(object.pos, "a second camera; a scene has exactly one");
            have_camera_ = true;
            start_line(object.pos);
            camera(object);
            return;
        case Category::surface:
            fail(object.pos, std::string("a ") + object.kind->keyword +
                                 " surface on its own does nothing: give it to an object "
                                 "(surface NAME) or make it the default (default_surface NAME)");
        case Category::group:
            break;
    }
}

void Emitter::default_surface(const ObjectValue& s, SourcePos pos) {
    start_line(pos);
    number(105);
    surface(s);
    have_default_surface_ = true;
}

void Emitter::finish(SourcePos end) {
    if (!have_camera_) fail(end, "no camera in the scene; one is required");
    if (line_open_) out_ += '\n';
    line_open_ = false;
}

void Emitter::shape(const ObjectValue& object, const Frame& placed) {
    mark(object.pos);
    if (!placed.is_identity()) frame(7, placed);
    numbers(object);
}

// The kind's ID, then its fields in the contract's order, each as its row says; a composite's
// operands instead.
void Emitter::numbers(const ObjectValue& object) {
    const Fields f(object);
    int id = object.kind->id;
    for (const FieldSpec& spec : object.kind->fields)
        if (spec.id != 0 && f.number(spec.name) != 0) id = spec.id;
    number(id);
    if (object.kind->category == Category::csg) return csg_operands(object);
    for (const FieldSpec& spec : object.kind->fields) field(object, spec);
}

void Emitter::field(const ObjectValue& object, const FieldSpec& spec) {
    const Fields f(object);
    switch (spec.write) {
        case Write::number:
            return number(f.number(spec.name));
        case Write::vector:
            return vector(f.vector(spec.name));
        case Write::surface:
            return surface(*f.value(spec.name).object);
        case Write::slot:
            return surface_slot(object);
        case Write::file:
            return file(object, spec.name);
        case Write::size: {
            const rt::Vec3 size = f.vector(spec.name);
            number(size.x);
            number(size.y);
            return;
        }
        case Write::cosine_or_degrees: {
            const bool cosine = f.one_of(spec.name, spec.other) == spec.name;
            return number(cosine ? f.number(spec.name) : cos_degrees(f.number(spec.other)));
        }
        case Write::three:
            for (const FieldValue* v : f.count(spec.name, 3, 3)) vector(v->value.vector);
            return;
        case Write::counted: {
            const auto list = f.count(spec.name, 3, static_cast<std::size_t>(limits_.list_items));
            number(static_cast<double>(list.size()));
            for (const FieldValue* v : list) vector(v->value.vector);
            return;
        }
        case Write::indexed:
        case Write::indexed_normals:
            return indexed(object, spec);
        case Write::none:
            return;
    }
}

// A union or intersection of more than two is nested to the right (A op (B op C)); a
// difference of more than two takes all the others from the first: A - (B u C u ...).
void Emitter::csg_operands(const ObjectValue& object) {
    const auto& operands = object.children;
    if (operands.size() < 2)
        fail(object.pos, std::string(object.kind->keyword) + " needs at least two objects, got " +
                             std::to_string(operands.size()));
    const auto operand = [&](const ObjectValue& o) {
        const Category c = o.kind->category;
        if (c != Category::primitive && c != Category::csg)
            fail(o.pos, std::string("a ") + o.kind->keyword + " cannot be part of a " +
                            object.kind->keyword);
        shape(o, o.transform);
    };
    for (std::size_t i = 0; i + 1 < operands.size(); ++i) {
        operand(*operands[i]);
        if (i + 2 < operands.size()) number(object.kind->rest_id);
    }
    operand(*operands.back());
}

// A mesh: the counts, the vertices, then the triangles' vertex indices, each checked.
void Emitter::indexed(const ObjectValue& object, const FieldSpec& spec) {
    const Fields f(object);
    const auto list = f.all(spec.name);
    const auto triangles = f.all(spec.other);
    if (list.empty() || triangles.empty())
        fail(object.pos, std::string(object.kind->keyword) + " needs at least one " + spec.name +
                             " and one " + spec.other);
    const bool normals = spec.write == Write::indexed_normals;
    const auto normal = normals ? f.all("normal") : decltype(list){};
    if (normals && normal.size() != list.size())
        fail(object.pos, std::string(object.kind->keyword) + " needs one normal per vertex (" +
                             std::to_string(list.size()) + " vertices, " +
                             std::to_string(normal.size()) + " normals)");
    number(static_cast<double>(list.size()));
    number(static_cast<double>(triangles.size()));
    for (std::size_t i = 0; i < list.size(); ++i) {
        vector(list[i]->value.vector);
        if (normals) vector(normal[i]->value.vector);
    }
    const double count = static_cast<double>(list.size());
    for (const FieldValue* t : triangles) {
        for (int i = 0; i < 3; ++i) {
            const double index = t->value.vector[i];
            if (index != std::floor(index) || index < 0 || index >= count)
                fail(t->pos, std::string(object.kind->keyword) + " " + spec.other +
                                 " indices must be whole numbers from 0 to " +
                                 std::to_string(list.size() - 1) + ", got " +
                                 std::to_string(index));
        }
        vector(t->value.vector);
    }
}

void Emitter::surface_slot(const ObjectValue& object) {
    if (const FieldValue* s = object.find("surface")) return surface(*s->value.object);
    if (!have_default_surface_)
        fail(object.pos, std::string(object.kind->keyword) +
                             ": missing field 'surface' (and no default_surface is set)");
    number(106);
}

void Emitter::surface(const ObjectValue& s) {
    if (!s.transform.is_identity()) frame(111, s.transform);
    numbers(s);
}

// Relative to the file that names it, written relative to where rtpp runs: where rt reading
// the output from a pipe looks for it.
void Emitter::file(const ObjectValue& object, const char* name) {
    const Fields f(object);
    const std::filesystem::path written(f.value(name).text);
    const SourcePos at = f.pos_of(name);
    const std::string path =
        written.is_absolute()
            ? written.string()
            : (files_[at.file].path.parent_path() / written).lexically_normal().string();
    if (path.find_first_of("\"\n") != std::string::npos)
        fail(at, "a file name cannot contain '\"' or a newline");
    word("\"" + path + "\"");
}

// The viewer's numbers as they are, or a camera's computed from all its fields together. The
// size is asked for first.
void Emitter::camera(const ObjectValue& object) {
    const Fields f(object);
    const rt::Vec3 size = f.vector("size");
    if (object.kind->category == Category::viewer) return numbers(object);
    number(object.kind->id);
    Camera c;
    c.position = f.vector("position");
    c.look_at = f.vector("look_at");
    c.up = f.vector("up");
    c.width = static_cast<int>(size.x);
    c.height = static_cast<int>(size.y);
    c.upright = f.number("upright") != 0;
    if (f.one_of("fov", "half_width") == std::string_view("fov")) {
        const double fov = f.number("fov");
        if (!(fov > 0 && fov < 180))
            fail(f.pos_of("fov"),
                 "camera fov must be between 0 and 180 degrees, got " + std::to_string(fov));
        c.half_width = tan_degrees(fov / 2);
    } else {
        c.half_width = f.number("half_width");
        if (!(c.half_width > 0)) fail(f.pos_of("half_width"), "camera half_width must be > 0");
    }
    try {
        const ViewerVectors v = viewer_vectors(c);
        vector(c.position);
        vector(c.look_at);
        vector(v.x);
        vector(v.y);
    } catch (const std::invalid_argument& e) {
        fail(object.pos, e.what());
    }
    number(size.x);
    number(size.y);
}

}  // namespace rtpp
