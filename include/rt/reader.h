// The scene reader: turns the numeric scene format into a Scene, or throws rt::Error naming
// the file, line and column of the first problem.
#pragma once

#include <filesystem>
#include <functional>
#include <istream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rt/error.h"
#include "rt/light.h"
#include "rt/limits.h"  // the bounds the reader holds a scene to
#include "rt/primitive.h"
#include "rt/scene.h"
#include "rt/shape_arena.h"
#include "rt/surface.h"

namespace rt {

class Sha256;  // common/digest.h

struct Image;
struct MeshFile;
class Lexer;
class MeshFileCache;
class TextureCache;

// A file a scene reads besides itself, resolved against the scene's directory: what an image
// made from the scene depends on (-M), and what its output must not replace.
struct SceneInput {
    std::filesystem::path path;
    const char* role;  // how messages name it: "the texture", "the mesh file"
};

// What an object made from a mesh file (15) holds: its shape, and how many zero-area
// triangles the file's mesh left out.
struct FileMeshShape {
    ShapeData shape;
    std::size_t kept = 0;  // the triangles it holds
    std::size_t skipped = 0;
};
// Makes the shape from what the file holds; throws rt::Error("<reason>") without a place.
using MakeFileMesh = std::function<FileMeshShape(const MeshFile&)>;

// Reads one scene. The read functions of the object tables call back into it for their
// numbers, so every error they report carries a place in the file.
class SceneReader {
  public:
    // name is used in messages ("<stdin>" for standard input); relative texture paths are
    // resolved against base_dir. Objects that build hierarchies of their own (meshes) build
    // them on up to `threads` threads; what they build is the same for any number.
    SceneReader(std::istream& in, std::string name, std::filesystem::path base_dir,
                int threads = 1);
    ~SceneReader();
    SceneReader(const SceneReader&) = delete;
    SceneReader& operator=(const SceneReader&) = delete;

    // The scene as read, without its hierarchy (Scene::build_index builds it).
    Scene read_scene();

    // Field readers; `what` names the field in messages ("sphere radius").
    double number(std::string_view what);
    // Reads the next token when it is a plain decimal number (digits, a point and fraction, an
    // exponent: what scenes are made of, see reader.cpp) and returns true with the value
    // number() gives for it; otherwise reads nothing and returns false, and number() reads the
    // token or reports it. For readers of many numbers whose field names cost something to
    // make: they make the name only when this returns false.
    bool plain_number(double& value);
    // Where the number last read began.
    Location last_number_location() const { return last_number_; }
    double positive(std::string_view what);      // > 0
    double non_negative(std::string_view what);  // >= 0
    Vec3 vec3(std::string_view what);
    // A vector whose length matters (a viewer's x vector): zero, or too short or too long for
    // its squared length to be a normal double, is an error.
    Vec3 nonzero_vec3(std::string_view what);
    // A direction, returned as a unit vector: any non-zero vector, however short. With
    // `length`, the vector's length as written is stored there.
    Vec3 direction(std::string_view what, double* length = nullptr);
    // The number last read as it was written, for messages (cut and escaped).
    std::string last_number_text() const;
    long whole(std::string_view what, long min, long max);
    std::string path(std::string_view what);
    // Reads a texture path and loads the image it names (relative to the scene's directory).
    // Each file (by device and inode) is loaded once per scene however many surfaces name it,
    // by whatever path.
    std::shared_ptr<const Image> texture(std::string_view what);
    // Reads a mesh file path (as texture() does) and returns the shape `make` makes from the
    // file for `mode` (ID 15). The file is read the first time any object names it, by
    // whatever path; `make` runs the first time it is named with this mode, and later
    // objects share that shape. What the file held and rt ignored becomes the scene's notes.
    ShapeData mesh_file(std::string_view what, int mode, const MakeFileMesh& make);
    // Every path that named a texture or a mesh file so far, each once, in the order first
    // named.
    const std::vector<SceneInput>& input_files() const { return inputs_; }
    // How many texture files were loaded: one per file, whatever it was called.
    std::size_t textures_loaded() const;
    // How many mesh files were read: one per file, whatever it was called.
    std::size_t mesh_files_read() const;

    // Nested objects: an inner primitive (ID and numbers, no surface), a surface (ID and
    // numbers, or 106 for the current default), a positioned light (ID and numbers).
    Shape shape(std::string_view what);
    SurfacePtr surface();
    Light light(std::string_view what);

    int threads() const { return threads_; }
    // A mesh reports the triangles it holds and the zero-area ones it skipped; the scene
    // carries the totals.
    void count_mesh_triangles(std::size_t kept, std::size_t skipped) {
        mesh_triangles_ += kept;
        skipped_triangles_ += skipped;
    }
    std::size_t skipped_triangles() const { return skipped_triangles_; }
    // A surface read reflects and transmits from one hit (Scene::splits_rays).
    void note_splitting_surface() { splits_rays_ = true; }

    // Where the next token starts: read it before a field to report errors about that field.
    Location next_location();
    [[noreturn]] void fail(Location where, std::string_view message) const;
    std::filesystem::path resolve(const std::string& path) const;

    // A primitive's parameters as its shape holds them: a small one in this reader's arena
    // (rt/shape_arena.h), which the scene's shapes keep alive, others allocated alone.
    template <class T>
    ShapeData shape_data(T value) {
        return make_shape_data(shape_arena_, std::move(value));
    }
    // Room of any size in the same arena, for parameters that need no destructor but have
    // arrays of their own (a polygon's outline, placed after it): fill it, then hand it to
    // placed_shape_data. One placement instead of an allocation per array, and no fresh heap
    // pages per polygon.
    void* shape_room(std::size_t bytes, std::size_t alignment) {
        return arena_made(shape_arena_).place(bytes, alignment);
    }
    ShapeData placed_shape_data(const void* placed) const { return {shape_arena_, placed}; }

  private:
    // The arena, made on first use.
    const std::shared_ptr<ShapeArena>& arena() {
        arena_made(shape_arena_);
        return shape_arena_;
    }
    void add_input(const std::filesystem::path& resolved, const char* role);

    // Counts nesting depth while an affine or checker reads what it holds.
    class Nest {
      public:
        Nest(SceneReader& reader, Location where);
        ~Nest() { --reader_.depth_; }
        Nest(const Nest&) = delete;
        Nest& operator=(const Nest&) = delete;

      private:
        SceneReader& reader_;
    };

    // Where an object began and how many numbers had been read then, for the note that an
    // error at the next object ID adds (a miscounted object shows up one object later).
    struct ObjectStart {
        long id = 0;
        Location where;
        long numbers_before = 0;
        bool known = false;
    };
    void begin_object(long type_id, Location where, bool top_level);
    std::string previous_object_note(Location error_at, long numbers_read,
                                     Location last_number) const;
    [[noreturn]] void fail_at_object_id(Location where, std::string_view message, long numbers_read,
                                        Location last_number) const;

    long id(std::string_view what);
    double written_number(std::string_view what);  // number() for a token not plain_number's
    void read_top_level_object(Scene& scene, bool& have_viewer);
    Viewer read_viewer();

    // Behind pointers, so that this header needs neither: one indirection per token.
    std::unique_ptr<Lexer> lexer_;
    std::unique_ptr<TextureCache> textures_;
    std::unique_ptr<MeshFileCache> mesh_files_;
    std::shared_ptr<ShapeArena> shape_arena_;  // made on first use
    std::vector<SceneInput> inputs_;
    std::vector<std::string> notes_;  // become Scene::notes
    std::filesystem::path base_dir_;
    SurfacePtr default_surface_;
    std::optional<Location> background_where_;  // where the scene's 115 is, once read
    int depth_ = 0;
    long numbers_read_ = 0;          // every number token so far, IDs included
    Location last_number_;           // where the last of them began
    std::string last_number_text_;   // and how it was written, or, when that was a plain
    char last_plain_text_[32] = {};  // decimal (plain_number), there: last_plain_size_ bytes
    unsigned char last_plain_size_ = 0;
    long light_samples_ = 0;        // taken by the lights so far
    ObjectStart last_object_;       // the object (at any depth) whose ID was read last
    ObjectStart top_level_object_;  // the top-level object that holds it
    std::size_t mesh_triangles_ = 0;
    std::size_t skipped_triangles_ = 0;
    bool splits_rays_ = false;
    int threads_ = 1;
};

// A number rt computed as messages show it (%g); numbers read are shown as written. Defined
// with the other message helpers (src/common/message_text.cpp); declared here too for the
// read functions, which report what they computed.
std::string format_number(double value);

// Seconds spent in each stage of a run: the scene's loading fills read and build, rt's job
// the rest (--stats prints them).
struct StageTimes {
    double read = 0;    // reading and checking the scene
    double build = 0;   // building its hierarchy
    double render = 0;  // tracing every pixel
    double write = 0;   // encoding and writing the image
};

// Convenience wrappers: read a whole scene from a stream or a file ("-" for stdin) and build
// its hierarchy on up to `threads` threads. With `times`, the seconds spent reading and
// building are stored in it; with `inputs`, the textures and mesh files the scene read
// (SceneReader::input_files()); with `digest`, every byte of the scene file (or standard
// input) is given to it as it is read.
Scene read_scene(std::istream& in, const std::string& name,
                 const std::filesystem::path& base_dir = {}, int threads = 1,
                 StageTimes* times = nullptr, std::vector<SceneInput>* inputs = nullptr);
Scene read_scene_file(const std::string& path, int threads = 1, StageTimes* times = nullptr,
                      std::vector<SceneInput>* inputs = nullptr, Sha256* digest = nullptr);

}  // namespace rt
