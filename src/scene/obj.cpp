// The Wavefront OBJ reader: one pass over the text keeps positions, normals and the face
// corners (position and normal index pairs, fan-triangulated); a last pass turns corners into
// rt's per-vertex model, splitting a position whose corners carry different normals.
#include <array>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "rt/error.h"
#include "scene/mesh_file.h"

namespace rt {

namespace {

using mesh_detail::parse_finite;
using mesh_detail::quoted_token;
using mesh_detail::text_place;

constexpr std::uint32_t kNone = 0xffffffffU;

struct Corner {
    std::uint32_t position;
    std::uint32_t normal;  // kNone without one
};

// Statements of the OBJ format that rt reads and ignores, each noted once.
struct Ignored {
    std::string_view keyword;
    const char* note;
};

constexpr Ignored kIgnored[] = {
    {"vt", "OBJ texture coordinates (vt) ignored"},
    {"o", "OBJ object names (o) ignored"},
    {"g", "OBJ groups (g) ignored"},
    {"s", "OBJ smoothing groups (s) ignored"},
    {"usemtl", "OBJ materials (usemtl) ignored"},
    {"mtllib", "OBJ material libraries (mtllib) ignored"},
    {"l", "OBJ lines (l) ignored"},
    {"p", "OBJ points (p) ignored"},
    // Free-form geometry, its attributes and the rest of the format: rt reads polygons only.
    {"vp", nullptr},
    {"cstype", nullptr},
    {"deg", nullptr},
    {"bmat", nullptr},
    {"step", nullptr},
    {"curv", nullptr},
    {"curv2", nullptr},
    {"surf", nullptr},
    {"parm", nullptr},
    {"trim", nullptr},
    {"hole", nullptr},
    {"scrv", nullptr},
    {"sp", nullptr},
    {"end", nullptr},
    {"con", nullptr},
    {"mg", nullptr},
    {"bevel", nullptr},
    {"c_interp", nullptr},
    {"d_interp", nullptr},
    {"lod", nullptr},
    {"maplib", nullptr},
    {"usemap", nullptr},
    {"shadow_obj", nullptr},
    {"trace_obj", nullptr},
    {"ctech", nullptr},
    {"stech", nullptr},
    {"call", nullptr},
    {"csh", nullptr},
};
constexpr std::size_t kIgnoredCount = sizeof kIgnored / sizeof kIgnored[0];

constexpr bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }
constexpr bool is_line_end(char c) { return c == '\n' || c == '\r'; }
constexpr bool is_digit(char c) { return c >= '0' && c <= '9'; }

class ObjReader {
  public:
    ObjReader(std::string_view bytes, const std::string& name)
        : bytes_(bytes), p_(bytes.data()), end_(bytes.data() + bytes.size()), name_(name) {}

    MeshFile read() {
        // A byte-order mark, as some Windows programs write, is not a statement.
        if (bytes_.substr(0, 3) == "\xEF\xBB\xBF") p_ += 3;
        while (p_ < end_) {
            skip_blanks();
            if (at_statement_end()) {
                end_statement();
                continue;
            }
            const char* keyword = p_;
            while (!is_delimiter(p_)) ++p_;
            const std::string_view k(keyword, static_cast<std::size_t>(p_ - keyword));
            if (k == "v") {
                vertex();
            } else if (k == "f") {
                face(keyword);
            } else if (k == "vn") {
                normal();
            } else {
                other(k, keyword);
            }
        }
        return finish();
    }

  private:
    [[noreturn]] void fail(const char* at, const std::string& what) const {
        const mesh_detail::TextPlace place =
            text_place(bytes_, static_cast<std::size_t>(at - bytes_.data()));
        throw Error(name_ + ":" + std::to_string(place.line) + ":" + std::to_string(place.column) +
                    ": " + what);
    }

    // A backslash that ends a line joins the next line to it.
    bool continuation(const char* q) const {
        return *q == '\\' && (q + 1 == end_ || is_line_end(q[1]));
    }

    void skip_line_end() {
        if (p_ < end_ && *p_ == '\r') ++p_;
        if (p_ < end_ && *p_ == '\n') ++p_;
    }

    void skip_blanks() {
        for (;;) {
            while (p_ < end_ && is_blank(*p_)) ++p_;
            if (p_ == end_ || !continuation(p_)) return;
            ++p_;
            skip_line_end();
        }
    }

    bool at_statement_end() const { return p_ == end_ || is_line_end(*p_) || *p_ == '#'; }

    bool is_delimiter(const char* q) const {
        return q == end_ || is_blank(*q) || is_line_end(*q) || *q == '#' || continuation(q);
    }

    // What a message says was found at q.
    std::string found(const char* q) const {
        if (q == end_) return "the end of the file";
        if (is_line_end(*q)) return "the end of the line";
        if (*q == '#') return "a comment";
        if (is_blank(*q)) return "white space";
        const char* e = q;
        while (e < end_ && !is_blank(*e) && !is_line_end(*e)) ++e;
        return quoted_token({q, static_cast<std::size_t>(e - q)});
    }

    // After a statement: a comment may follow, then the line ends.
    void end_statement() {
        skip_blanks();
        if (!at_statement_end()) fail(p_, "expected the end of the line, found " + found(p_));
        while (p_ < end_ && !is_line_end(*p_)) ++p_;
        skip_line_end();
    }

    // Skips an ignored statement's arguments, continuations included.
    void skip_statement() {
        while (p_ < end_ && !is_line_end(*p_)) {
            if (continuation(p_)) {
                ++p_;
                skip_line_end();
            } else {
                ++p_;
            }
        }
        skip_line_end();
    }

    double number(const char* what) {
        skip_blanks();
        double v = 0;
        const char* e = parse_finite(p_, end_, v);
        if (e == nullptr || !is_delimiter(e))
            fail(p_, std::string("expected ") + what + ", found " + found(p_));
        p_ = e;
        return v;
    }

    void vertex() {
        if (positions_.size() >= kMaxMeshElements)
            fail(p_,
                 "expected at most " + std::to_string(kMaxMeshElements) + " vertices, found more");
        const double x = number("a coordinate (x)");
        const double y = number("a coordinate (y)");
        const double z = number("a coordinate (z)");
        positions_.push_back({x, y, z});
        // Up to four more numbers: a weight w, or a colour (r g b, or r g b a).
        skip_blanks();
        if (!at_statement_end()) {
            for (int extra = 0; extra < 4 && !at_statement_end(); ++extra) {
                number("a number (a weight or a colour) or the end of the line");
                skip_blanks();
            }
            note_once(vertex_extras_noted_, "OBJ vertex weights and colours ignored");
        }
        end_statement();
    }

    void normal() {
        if (normals_.size() >= kMaxMeshElements)
            fail(p_,
                 "expected at most " + std::to_string(kMaxMeshElements) + " normals, found more");
        const double x = number("a normal component (x)");
        const double y = number("a normal component (y)");
        const double z = number("a normal component (z)");
        normals_.push_back({x, y, z});
        end_statement();
    }

    // An index of a face corner, resolved to zero-based: 1 is the first element, -1 the last
    // defined so far. Only elements defined before the face may be named.
    std::uint32_t index(std::uint64_t count, const char* what, const char* plural) {
        const char* start = p_;
        const bool negative = p_ < end_ && *p_ == '-';
        if (p_ < end_ && (*p_ == '-' || *p_ == '+')) ++p_;
        if (p_ == end_ || !is_digit(*p_))
            fail(start, std::string("expected ") + what + ", found " + found(start));
        std::uint64_t v = 0;
        for (; p_ < end_ && is_digit(*p_); ++p_)
            if (v <= kMaxMeshElements) v = v * 10 + static_cast<std::uint64_t>(*p_ - '0');
        if (v == 0 || v > count) {
            const std::string text = quoted_token({start, static_cast<std::size_t>(p_ - start)});
            if (count == 0)
                fail(start, std::string("expected ") + what + ", found " + text + ", but no " +
                                plural + " are defined before this face");
            fail(start, std::string("expected ") + what + " from 1 to " + std::to_string(count) +
                            " or from -" + std::to_string(count) + " to -1, found " + text);
        }
        return static_cast<std::uint32_t>(negative ? count - v : v - 1);
    }

    Corner corner() {
        Corner c{index(positions_.size(), "a vertex index", "vertices"), kNone};
        if (p_ < end_ && *p_ == '/') {
            ++p_;
            if (p_ < end_ && *p_ == '/') {
                ++p_;
            } else {
                index(texcoords_, "a texture-coordinate index", "texture coordinates");
                note_once(texture_indices_noted_, "OBJ texture-coordinate indices ignored");
                if (p_ < end_ && *p_ == '/') {
                    ++p_;
                } else {
                    if (!is_delimiter(p_))
                        fail(p_, "expected '/' or the end of the corner, found " + found(p_));
                    return c;
                }
            }
            c.normal = index(normals_.size(), "a normal index", "normals");
            if (!is_delimiter(p_)) fail(p_, "expected the end of the corner, found " + found(p_));
            return c;
        }
        if (!is_delimiter(p_))
            fail(p_, "expected '/' or the end of the corner, found " + found(p_));
        return c;
    }

    void face(const char* keyword) {
        std::uint64_t n = 0;
        Corner first{}, previous{};
        for (;;) {
            skip_blanks();
            if (at_statement_end()) break;
            const Corner c = corner();
            if (n == 0) {
                first = c;
            } else if (n >= 2) {
                if (triangles_.size() >= kMaxMeshElements)
                    fail(keyword, "expected at most " + std::to_string(kMaxMeshElements) +
                                      " triangles, found more");
                triangles_.push_back({first, previous, c});
            }
            previous = c;
            ++n;
        }
        if (n < 3)
            fail(keyword, "expected a face of at least 3 vertices, found " + std::to_string(n));
        end_statement();
    }

    void other(std::string_view k, const char* keyword) {
        for (std::size_t i = 0; i < kIgnoredCount; ++i) {
            if (kIgnored[i].keyword != k) continue;
            if (i == 0) ++texcoords_;
            if (!ignored_noted_[i]) {
                ignored_noted_[i] = true;
                notes_.push_back(kIgnored[i].note != nullptr
                                     ? std::string(kIgnored[i].note)
                                     : "OBJ '" + std::string(k) +
                                           "' statements ignored (rt reads polygons only)");
            }
            skip_statement();
            return;
        }
        fail(keyword,
             "expected an OBJ statement (v, vn, vt, f, o, g, s, usemtl, mtllib, l, p, "
             "...), found " +
                 quoted_token(k));
    }

    void note_once(bool& noted, const char* text) {
        if (noted) return;
        noted = true;
        notes_.emplace_back(text);
    }

    MeshFile finish() {
        MeshFile mesh;
        mesh.notes = std::move(notes_);
        std::uint64_t with_normals = 0;
        for (const auto& t : triangles_)
            for (const Corner& c : t) with_normals += c.normal != kNone ? 1 : 0;
        const std::uint64_t corners = 3 * static_cast<std::uint64_t>(triangles_.size());
        if (with_normals > 0 && with_normals < corners)
            mesh.notes.emplace_back(
                "OBJ face corners without a normal: their triangles have no vertex normals "
                "(flat in mode 0, computed in mode 2)");
        mesh.positions = std::move(positions_);
        mesh.triangles.reserve(triangles_.size());
        if (with_normals == 0) {
            for (const auto& t : triangles_)
                mesh.triangles.push_back({t[0].position, t[1].position, t[2].position});
            return mesh;
        }
        split_by_normals(mesh);
        return mesh;
    }

    // A corner without a normal has the zero normal, which marks its vertex as having none.
    Vec3 normal_of(const Corner& c) const {
        return c.normal == kNone ? Vec3{} : normals_[c.normal];
    }

    // A position takes the normal of the first corner that names it; a corner with another
    // normal (by value: files often repeat one normal under several indices), or with none
    // where the first had one, gets a copy of the position, one per distinct (position,
    // normal index) pair.
    void split_by_normals(MeshFile& mesh) {
        const std::size_t count = mesh.positions.size();
        mesh.normals.assign(count, Vec3{});
        constexpr std::uint32_t kUnused = kNone - 1;  // no corner has named the position yet
        std::vector<std::uint32_t> first(count, kUnused);
        std::unordered_map<std::uint64_t, std::uint32_t> copies;
        for (const auto& t : triangles_) {
            std::array<std::uint32_t, 3> out{};
            for (int k = 0; k < 3; ++k) {
                const Corner c = t[static_cast<std::size_t>(k)];
                std::uint32_t& id = out[static_cast<std::size_t>(k)];
                if (first[c.position] == kUnused) {
                    first[c.position] = c.normal;
                    mesh.normals[c.position] = normal_of(c);
                    id = c.position;
                } else if (first[c.position] == c.normal ||
                           mesh.normals[c.position] == normal_of(c)) {
                    id = c.position;
                } else {
                    const std::uint64_t key = std::uint64_t{c.position} << 32 | c.normal;
                    const auto [it, added] =
                        copies.try_emplace(key, static_cast<std::uint32_t>(mesh.positions.size()));
                    if (added) {
                        if (mesh.positions.size() >= kMaxMeshElements)
                            throw Error(name_ + ": expected at most " +
                                        std::to_string(kMaxMeshElements) +
                                        " vertices after giving each distinct corner normal "
                                        "its own vertex, found more");
                        const Vec3 position = mesh.positions[c.position];
                        mesh.positions.push_back(position);
                        mesh.normals.push_back(normal_of(c));
                    }
                    id = it->second;
                }
            }
            mesh.triangles.push_back(out);
        }
    }

    std::string_view bytes_;
    const char* p_;
    const char* end_;
    const std::string& name_;
    std::vector<Vec3> positions_;
    std::vector<Vec3> normals_;
    std::uint64_t texcoords_ = 0;
    std::vector<std::array<Corner, 3>> triangles_;
    std::vector<std::string> notes_;
    bool ignored_noted_[kIgnoredCount] = {};
    bool vertex_extras_noted_ = false;
    bool texture_indices_noted_ = false;
};

}  // namespace

MeshFile read_obj(std::string_view bytes, const std::string& display_name) {
    return ObjReader(bytes, display_name).read();
}

}  // namespace rt
