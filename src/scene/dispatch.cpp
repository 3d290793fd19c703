// The dispatch: object IDs at the top level and nested (shapes, surfaces, lights), the viewer,
// and the note that places an error at an object ID after the object before it.
#include <cctype>
#include <string>

#include "rt/error.h"
#include "rt/reader.h"
#include "scene/lexer.h"

namespace rt {

namespace {

// IDs the reader handles itself rather than through a table.
constexpr long kViewerId = 102;
constexpr long kAmbientLightId = 103;
constexpr long kBackgroundId = 115;
constexpr long kDefaultSurfaceId = 105;
constexpr long kUseDefaultSurfaceId = 106;

// What an ID is, for messages that say what was found instead of what was expected.
std::string describe_id(long id) {
    if (id == kViewerId) return "102 (viewer)";
    if (id == kAmbientLightId) return "103 (ambient light)";
    if (id == kBackgroundId) return "115 (background)";
    if (id == kDefaultSurfaceId) return "105 (default surface)";
    if (id == kUseDefaultSurfaceId) return "106 (use default surface)";
    const int small = static_cast<int>(id);
    if (const PrimitiveType* p = find_primitive_type(small))
        return std::to_string(id) + " (" + p->name + ")";
    if (const SurfaceType* s = find_surface_type(small))
        return std::to_string(id) + " (" + s->name + ")";
    if (const LightType* l = find_light_type(small))
        return std::to_string(id) + " (" + l->name + ")";
    return std::to_string(id);
}

// "simple surface 100": what an object is, for the note about the previous object.
std::string name_id(long id) {
    const std::string described = describe_id(id);
    const auto paren = described.find(" (");
    if (paren == std::string::npos) return "object " + described;
    return described.substr(paren + 2, described.size() - paren - 3) + " " +
           described.substr(0, paren);
}

std::string line_and_column(Location where) {
    return std::to_string(where.line) + ":" + std::to_string(where.column);
}

}  // namespace

Shape SceneReader::shape(std::string_view what) {
    const Location where = next_location();
    const Nest nest(*this, where);
    const long type_id = id(std::string(what) + " ID");
    begin_object(type_id, where, false);
    const PrimitiveType* type = find_primitive_type(static_cast<int>(type_id));
    if (type == nullptr)
        fail(where, "expected " + std::string(what) + " ID (a primitive, 1-99), got " +
                        describe_id(type_id));
    return {type, type->functions->read(*this)};
}

SurfacePtr SceneReader::surface() {
    const Location where = next_location();
    const Nest nest(*this, where);
    const long type_id = id("surface ID");
    begin_object(type_id, where, false);
    if (type_id == kUseDefaultSurfaceId) {
        if (!default_surface_)
            fail(where, "106 (use default surface) but no default surface has been set with 105");
        return default_surface_;
    }
    const SurfaceType* type = find_surface_type(static_cast<int>(type_id));
    if (type == nullptr) {
        std::string ids;
        bool listed_default = false;
        for (const SurfaceType& row : surface_types()) {
            if (!listed_default && row.id > kUseDefaultSurfaceId) {
                ids += ", " + std::to_string(kUseDefaultSurfaceId);
                listed_default = true;
            }
            ids += (ids.empty() ? "" : ", ") + std::to_string(row.id);
        }
        fail(where, "expected a surface ID (one of " + ids + "), got " + describe_id(type_id));
    }
    // In the arena with its count, as the shapes are: a scene that sets a surface per object
    // (the SPD's lattice) makes thousands.
    SurfaceData data = type->read(*this);
    return std::allocate_shared<const Surface>(ArenaAllocator<Surface>(arena()),
                                               Surface{type, std::move(data)});
}

Light SceneReader::light(std::string_view what) {
    const Location where = next_location();
    const Nest nest(*this, where);
    const long type_id = id(std::string(what) + " ID");
    begin_object(type_id, where, false);
    const LightType* type = find_light_type(static_cast<int>(type_id));
    if (type == nullptr)
        fail(where, "expected " + std::string(what) + " ID (a light with a position), got " +
                        describe_id(type_id));
    return {type, type->read(*this)};
}

Viewer SceneReader::read_viewer() {
    Viewer v;
    v.eye = vec3("viewer eye position");
    const Location look_where = next_location();
    v.look_at = vec3("viewer look-at point");
    if (!(length(v.look_at - v.eye) > 0))
        fail(look_where, "viewer look-at point must differ from the eye position");
    v.x = nonzero_vec3("viewer x vector");
    v.y = nonzero_vec3("viewer y vector");
    const Location res_where = next_location();
    v.xres = static_cast<int>(whole("viewer x resolution", 1, kMaxResolution));
    v.yres = static_cast<int>(whole("viewer y resolution", 1, kMaxResolution));
    if (static_cast<long>(v.xres) * v.yres > kMaxPixels)
        fail(res_where, "viewer resolution " + std::to_string(v.xres) + "x" +
                            std::to_string(v.yres) + " exceeds the limit of " +
                            std::to_string(kMaxPixels) + " pixels");
    return v;
}

void SceneReader::begin_object(long type_id, Location where, bool top_level) {
    last_object_ = {type_id, where, numbers_read_, true};
    if (top_level) top_level_object_ = last_object_;
}

std::string SceneReader::previous_object_note(Location error_at, long numbers_read,
                                              Location last_number) const {
    if (!last_object_.known) return {};
    const auto place = [&](Location at) {
        return at.file == error_at.file ? line_and_column(at) : lexer_->place(at);
    };
    const long count = numbers_read - last_object_.numbers_before;
    std::string note = "note: the previous object, " + name_id(last_object_.id) + " at " +
                       place(last_object_.where) + ", read " + std::to_string(count) +
                       (count == 1 ? " number" : " numbers");
    if (count > 0) note += " ending at " + place(last_number);
    const ObjectStart& top = top_level_object_;
    if (top.known && (top.where.line != last_object_.where.line ||
                      top.where.column != last_object_.where.column ||
                      top.where.file != last_object_.where.file))
        note += ", within " + name_id(top.id) + " at " + place(top.where) + " (" +
                std::to_string(numbers_read - top.numbers_before) + " numbers in all)";
    return note;
}

void SceneReader::fail_at_object_id(Location where, std::string_view message, long numbers_read,
                                    Location last_number) const {
    const std::string note = previous_object_note(where, numbers_read, last_number);
    if (note.empty()) fail(where, message);
    throw Error(lexer_->place(where) + ": " + std::string(message) + "\n" + lexer_->place(where) +
                ": " + note);
}

void SceneReader::read_top_level_object(Scene& scene, bool& have_viewer) {
    const Location where = next_location();
    // A bad token here is often a number too many or too few in the object before it, so
    // errors about the ID say where that object began and how much of the input it took.
    const long numbers_before = numbers_read_;
    const Location last_number_before = last_number_;
    long type_id = 0;
    // A word where the first ID should be is most likely rt's readable language, which rtpp
    // compiles: say so, rather than only that a number was expected.
    const std::string_view first_text = lexer_->peek().text;
    const bool word_first = numbers_before == 0 && !first_text.empty() &&
                            std::isalpha(static_cast<unsigned char>(first_text[0])) != 0;
    try {
        type_id = id("object ID");
    } catch (const Error& e) {
        if (word_first)
            throw Error(std::string(e.what()) + "\n" + lexer_->place(where) +
                        ": note: this looks like rt's readable scene language, which rtpp "
                        "compiles to the numeric format rt reads: rtpp SCENE.rts | rt -o "
                        "IMAGE");
        const std::string note = previous_object_note(where, numbers_before, last_number_before);
        if (note.empty()) throw;
        throw Error(std::string(e.what()) + "\n" + lexer_->place(where) + ": " + note);
    }
    const int small = static_cast<int>(type_id);
    const bool known = find_primitive_type(small) || find_light_type(small) ||
                       type_id == kViewerId || type_id == kAmbientLightId ||
                       type_id == kBackgroundId || type_id == kDefaultSurfaceId;
    if (!known) {
        if (find_surface_type(small) != nullptr || type_id == kUseDefaultSurfaceId)
            fail_at_object_id(where,
                              "surface " + describe_id(type_id) +
                                  " found where an object is expected; a surface must follow a "
                                  "primitive",
                              numbers_before, last_number_before);
        fail_at_object_id(where, "unknown object ID " + last_number_text(), numbers_before,
                          last_number_before);
    }
    begin_object(type_id, where, true);
    if (const PrimitiveType* type = find_primitive_type(small)) {
        Object object;
        object.shape = {type, type->functions->read(*this)};
        // CSG (and an affine of CSG) carries its operands' surfaces and has none of its own.
        if (!object.shape.carries_surfaces()) object.surface = surface();
        scene.objects.push_back(std::move(object));
    } else if (const LightType* light_type = find_light_type(small)) {
        scene.lights.push_back({light_type, light_type->read(*this)});
        light_samples_ += scene.lights.back().sample_count();
        if (light_samples_ > kMaxLightSamples)
            fail(where, "too many light samples: with this light the scene's lights take " +
                            std::to_string(light_samples_) + " samples, more than the limit of " +
                            std::to_string(kMaxLightSamples) +
                            " (each is a shadow ray for every point lit)");
    } else if (type_id == kViewerId) {
        if (have_viewer) fail(where, "a second viewer (102); a scene has exactly one");
        scene.viewer = read_viewer();
        have_viewer = true;
    } else if (type_id == kAmbientLightId) {
        const Vec3 intensity = vec3("ambient light intensity");
        scene.ambient += Spectrum(intensity.x, intensity.y, intensity.z);
    } else if (type_id == kBackgroundId) {
        if (const auto first = background_where_)
            fail(where,
                 "a second background (115); a scene has at most one, the first is at " +
                     (first->file == where.file ? line_and_column(*first) : lexer_->place(*first)));
        background_where_ = where;
        // Validated as the ambient intensity it stands in for: any finite numbers.
        const Vec3 colour = vec3("background colour");
        scene.background = Spectrum(colour.x, colour.y, colour.z);
    } else if (type_id == kDefaultSurfaceId) {
        default_surface_ = surface();
    }
}

Scene SceneReader::read_scene() {
    Scene scene;
    bool have_viewer = false;
    while (!lexer_->peek().at_end()) read_top_level_object(scene, have_viewer);
    if (numbers_read_ == 0)
        fail(lexer_->peek().where,
             lexer_->name() == "<stdin>"
                 ? "the scene is empty: nothing came on standard input (when a program writes "
                   "it, as in 'rtpp scene.rts | rt', see that program's error above)"
                 : "the scene is empty: the file holds no objects (and no viewer, 102, which "
                   "every scene needs)");
    if (!have_viewer) fail(lexer_->peek().where, "no viewer (102) in the scene; one is required");
    scene.skipped_triangles = skipped_triangles_;
    scene.mesh_triangles = mesh_triangles_;
    scene.notes = std::move(notes_);
    scene.splits_rays = splits_rays_;
    return scene;
}

}  // namespace rt
