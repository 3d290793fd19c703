// Writes objects in the numeric format, each top-level object on its own line, with
// `#line N "file"` markers wherever the output's lines stop following the source's, so that
// rt's messages name the readable source.
#pragma once

#include <optional>
#include <string>

#include "rtpp/limits.h"
#include "rtpp/source.h"
#include "rtpp/value.h"

namespace rtpp {

class Emitter {
  public:
    Emitter(const SourceFiles& files, const Limits& limits, std::string& out);

    // A top-level object: a primitive, CSG, group, light, ambient light, camera or viewer.
    void place(const ObjectValue& object);
    // A place in the sources as messages show it ("scene.rts:3:5").
    std::string where(SourcePos pos) const { return files_.place(pos); }
    // 105: later primitives without a surface take this one (106).
    void default_surface(const ObjectValue& surface, SourcePos pos);
    // The end of the program: a scene without a camera is an error here, at `end`.
    void finish(SourcePos end);

  private:
    void place_in(const ObjectValue& object, const Frame& parent);
    void start_line(SourcePos pos);
    void mark(SourcePos pos);
    void word(std::string_view text);
    void number(double value);
    void vector(const rt::Vec3& v);
    void frame(int id, const Frame& f);

    void shape(const ObjectValue& object, const Frame& frame);
    void numbers(const ObjectValue& object);
    void field(const ObjectValue& object, const FieldSpec& spec);
    void csg_operands(const ObjectValue& object);
    void indexed(const ObjectValue& object, const FieldSpec& spec);
    void surface_slot(const ObjectValue& object);
    void surface(const ObjectValue& surface);
    void file(const ObjectValue& object, const char* name);
    void camera(const ObjectValue& object);

    const SourceFiles& files_;
    const Limits& limits_;
    std::string& out_;
    bool line_open_ = false;  // the current output line has something on it
    int mapped_file_ = -1;    // the source place of the current (or next) output line
    int mapped_line_ = 0;
    long objects_ = 0;
    bool have_default_surface_ = false;
    bool have_camera_ = false;
    std::optional<SourcePos> background_;  // where the scene's background was written from
};

}  // namespace rtpp
