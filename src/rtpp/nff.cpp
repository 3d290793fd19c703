#include "rtpp/nff.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace rtpp {

using rt::Vec3;

NffViewer nff_viewer(const NffView& v) {
    const Vec3 view = v.at - v.from;
    const double distance = rt::length(view);
    if (!(distance > 0) || !std::isfinite(distance))
        throw std::invalid_argument("v: 'at' must differ from 'from'");
    const Vec3 d = view / distance;
    const Vec3 right_dir = rt::cross(d, v.up);
    const double right_len = rt::length(right_dir);
    if (!(right_len > 0) || !std::isfinite(right_len))
        throw std::invalid_argument("v: 'up' must not be zero or along the line of sight");
    const Vec3 r = right_dir / right_len;
    const Vec3 u = rt::cross(r, d);
    if (!(v.angle > 0 && v.angle < 180))
        throw std::invalid_argument("v: angle must be between 0 and 180 degrees");
    if (v.xres < 1 || v.yres < 1) throw std::invalid_argument("v: resolution must be >= 1");
    // Pixel pitch on the plane one unit ahead: the angle spans n - 1 pitches between the
    // first and the last pixel centre of the longer side (a single pixel spans it all).
    const int n = std::max(v.xres, v.yres);
    const double half = std::tan(v.angle * std::numbers::pi / 360);
    const double pitch = n > 1 ? 2 * half / (n - 1) : 2 * half;
    // rt's corner ray of pixel (0, 0) must be NFF's ray half a pixel further right and down:
    // moving the look-at by that half pixel moves every ray by it. rt then puts its image
    // plane at unit distance along the new line of sight, k = |d + shift| from the eye
    // instead of 1, so x and y shrink by k to keep the pitch.
    const Vec3 shift = (pitch / 2) * (r - u);
    const double k = std::sqrt(1 + pitch * pitch / 2);
    NffViewer out;
    out.eye = v.from;
    out.look_at = v.at + distance * shift;
    out.x = r * (v.xres * pitch / (2 * k));
    out.y = u * (v.yres * pitch / (2 * k));
    return out;
}

NffCone nff_cone(const Vec3& base, double base_radius, const Vec3& apex, double apex_radius) {
    const double len = rt::length(base - apex);
    if (!(len > 0)) throw std::invalid_argument("cone base and apex must differ");
    const double change = base_radius - apex_radius;
    if (change == 0) throw std::invalid_argument("cone radii are equal: a cylinder");
    if (base_radius < 0 || apex_radius < 0) throw std::invalid_argument("cone radii must be >= 0");
    NffCone c;
    // Scaled so that a point at distance r from the axis lies r axis-lengths from the apex.
    c.axis = (base - apex) / change;
    c.apex = base - base_radius * c.axis;
    c.alpha = len / std::hypot(len, change);
    c.start = std::min(base_radius, apex_radius);
    c.finish = std::max(base_radius, apex_radius);
    return c;
}

namespace {

struct Token {
    std::string_view text;  // empty at the end of the input
    long line = 0;
    long column = 0;
};

// What a message shows of a token: cut, since a hostile line may be a megabyte long.
std::string shown(std::string_view text) {
    constexpr std::size_t kMax = 40;
    return text.size() <= kMax ? std::string(text) : std::string(text.substr(0, kMax)) + "...";
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// What a number is, for messages ("pp vertex 3 normal x"): the pieces, joined into text only
// when a message needs it, so that reading a number costs no string building.
struct Label {
    // Implicit, so that a plain name ("s radius") is a label.
    Label(const char* base_name, long i = 0, const char* part_name = nullptr)  // NOLINT
        : base(base_name), index(i), part(part_name) {}

    const char* base;
    long index;                   // "vertex 3" when > 0
    const char* part;             // "normal"
    const char* piece = nullptr;  // a component: "x", "red"

    Label with_piece(const char* p) const {
        Label l = *this;
        l.piece = p;
        return l;
    }
    std::string text() const {
        // Appended piece by piece: g++ 12 warns falsely (-Wrestrict) about "a" + string chains.
        std::string t = base;
        if (index > 0) t.append(" ").append(std::to_string(index));
        if (part != nullptr) t.append(" ").append(part);
        if (piece != nullptr) t.append(" ").append(piece);
        return t;
    }
};

// Tokens with their places, read one line at a time; '#' starts a comment anywhere. A token
// stays valid until the token after the next one is read (one token of look-ahead).
class Lexer {
  public:
    Lexer(std::istream& in, const std::string& name, std::size_t max_line)
        : buf_(in.rdbuf()), name_(name), max_line_(max_line) {}

    Token next() {
        if (has_peek_) {
            has_peek_ = false;
            return peeked_;
        }
        return read();
    }
    const Token& peek() {
        if (!has_peek_) {
            peeked_ = read();
            has_peek_ = true;
        }
        return peeked_;
    }

    [[noreturn]] void fail(long line, long column, const std::string& message) const {
        throw CompileError(name_ + ":" + std::to_string(line) + ":" + std::to_string(column) +
                           ": " + message);
    }
    [[noreturn]] void fail(const Token& at, const std::string& message) const {
        fail(at.line, at.column, message);
    }

  private:
    Token read() {
        for (;;) {
            while (pos_ < line_.size() && is_space(line_[pos_])) ++pos_;
            if (pos_ < line_.size() && line_[pos_] != '#') {
                const std::size_t start = pos_;
                while (pos_ < line_.size() && !is_space(line_[pos_]) && line_[pos_] != '#') ++pos_;
                return {std::string_view(line_).substr(start, pos_ - start), line_number_,
                        static_cast<long>(start) + 1};
            }
            if (!read_line())
                return {{}, std::max(line_number_, 1L), static_cast<long>(line_.size()) + 1};
        }
    }

    bool read_line() {
        if (buf_ == nullptr || at_end_) return false;
        // At the end, the last line stays: the end of input is placed after it.
        if (buf_->sgetc() == std::char_traits<char>::eof()) {
            at_end_ = true;
            return false;
        }
        line_.clear();
        pos_ = 0;
        ++line_number_;
        for (;;) {
            const auto c = buf_->sbumpc();
            if (c == std::char_traits<char>::eof()) {
                at_end_ = true;
                return !line_.empty();
            }
            if (c == '\n') return true;
            if (line_.size() == max_line_)
                fail(line_number_, static_cast<long>(line_.size()) + 1,
                     "line longer than " + std::to_string(max_line_) + " bytes");
            line_ += static_cast<char>(c);
        }
    }

    std::streambuf* buf_;
    const std::string& name_;
    std::size_t max_line_;
    std::string line_;
    std::size_t pos_ = 0;
    long line_number_ = 0;
    bool at_end_ = false;
    bool has_peek_ = false;
    Token peeked_;
};

// The numeric scene, written so that its lines follow the source's: a word from source line
// N goes on the output line that a `#line` marker (or the lines since one) says is line N.
class Writer {
  public:
    Writer(std::ostream& out, const std::string& name)
        : out_(out), name_(name), markers_(name.find_first_of("\"\n") == std::string::npos) {
        std::string header = name;
        std::replace(header.begin(), header.end(), '\n', '?');
        buf_ = "# Written by rtpp from " + header + "; edit that, not this.\n";
    }

    // The next words come from source line `line`.
    void at(long line) {
        if (line == line_) return;
        // A short gap forward is cheaper as blank lines than as a marker.
        constexpr long kMaxGap = 8;
        if (markers_ && line_ > 0 && line > line_ && line - line_ <= kMaxGap) {
            buf_.append(static_cast<std::size_t>(line - line_), '\n');
        } else {
            if (open_) buf_ += '\n';
            if (markers_) buf_ += "#line " + std::to_string(line) + " \"" + name_ + "\"\n";
        }
        line_ = line;
        open_ = false;
    }
    void word(std::string_view text) {
        if (open_) buf_ += ' ';
        buf_ += text;
        open_ = true;
        if (buf_.size() >= kFlushAt) flush();
    }
    // The shortest text that reads back as the same double (-0 as 0).
    void number(double value) {
        if (value == 0) value = 0;
        char text[32];
        const auto result = std::to_chars(text, text + sizeof text, value);
        word(std::string_view(text, static_cast<std::size_t>(result.ptr - text)));
    }
    void whole(std::size_t value) { word(std::to_string(value)); }
    void vec(const Vec3& v) {
        number(v.x);
        number(v.y);
        number(v.z);
    }
    void finish() {
        if (open_) buf_ += '\n';
        open_ = false;
        flush();
        out_.flush();
    }

  private:
    static constexpr std::size_t kFlushAt = 1u << 16;
    void flush() {
        out_.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
        buf_.clear();
    }

    std::ostream& out_;
    const std::string& name_;
    bool markers_;  // a name a marker cannot quote gets none, as rtpp's emitter does
    std::string buf_;
    long line_ = 0;  // the source line of the current output line; 0 before the first
    bool open_ = false;
};

constexpr std::string_view kEntities = "v, b, l, f, c, s, p, pp";

class Translator {
  public:
    Translator(std::istream& in, const std::string& name, std::ostream& out,
               const NffOptions& options)
        : lex_(in, name, options.max_line_length), out_(out, name), options_(options) {}

    void run() {
        for (;;) {
            const Token t = lex_.next();
            if (t.text.empty()) return finish(t);
            if (t.text != "pp") flush_mesh();
            if (t.text == "v") {
                viewpoint(t);
            } else if (t.text == "b") {
                background(t);
            } else if (t.text == "l") {
                light(t);
            } else if (t.text == "f") {
                fill(t);
            } else if (t.text == "c") {
                cone(t);
            } else if (t.text == "s") {
                sphere(t);
            } else if (t.text == "p") {
                polygon(t);
            } else if (t.text == "pp") {
                patch(t);
            } else {
                lex_.fail(t, "unknown NFF entity '" + shown(t.text) + "' (NFF has " +
                                 std::string(kEntities) + ")");
            }
        }
    }

  private:
    static bool looks_numeric(std::string_view text) {
        if (text.empty()) return false;
        const char c = text[0];
        return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.';
    }

    // The next token as a finite number; `label` names it in messages.
    double number(const Label& label, Token* where = nullptr) {
        const Token t = lex_.next();
        if (where != nullptr) *where = t;
        const auto what = [&] { return label.text(); };
        if (t.text.empty()) lex_.fail(t, "end of file: expected " + what());
        std::string_view text = t.text;
        // strtod's forms, as rt reads them: from_chars takes neither a leading '+' nor hex.
        if (text.size() > 1 && text[0] == '+' && text[1] != '-' && text[1] != '+')
            text.remove_prefix(1);
        double value = 0;
        const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
        if (result.ec == std::errc::result_out_of_range)
            lex_.fail(t, what() + " is out of range: '" + shown(t.text) + "'");
        if (result.ec != std::errc() || result.ptr != text.data() + text.size())
            lex_.fail(t, "expected " + what() + ", got '" + shown(t.text) + "'");
        if (!std::isfinite(value))
            lex_.fail(t, what() + " must be finite, got '" + shown(t.text) + "'");
        return value;
    }
    Vec3 vec(const Label& label, Token* where = nullptr) {
        const double x = number(label.with_piece("x"), where);
        const double y = number(label.with_piece("y"));
        const double z = number(label.with_piece("z"));
        return {x, y, z};
    }
    double non_negative(const Label& label) {
        Token t;
        const double v = number(label, &t);
        if (v < 0) lex_.fail(t, label.text() + " must be >= 0, got '" + shown(t.text) + "'");
        return v;
    }
    Vec3 colour(const Label& label) {
        const double r = non_negative(label.with_piece("red"));
        const double g = non_negative(label.with_piece("green"));
        const double b = non_negative(label.with_piece("blue"));
        return {r, g, b};
    }
    long count(const Label& label, long min, long max, Token* where) {
        const double v = number(label, where);
        if (v != std::floor(v) || v < static_cast<double>(min) || v > static_cast<double>(max))
            lex_.fail(*where, label.text() + " must be a whole number from " + std::to_string(min) +
                                  " to " + std::to_string(max) + ", got '" + shown(where->text) +
                                  "'");
        return static_cast<long>(v);
    }

    void require_surface(const Token& t) {
        if (!have_surface_)
            lex_.fail(t, "'" + std::string(t.text) +
                             "' before any 'f': NFF gives each object the last 'f' before it");
    }

    // v, then from, at, up, angle, hither and resolution lines, in any order; hither (a
    // clipping distance for hidden-surface machines) is read and not used.
    void viewpoint(const Token& v) {
        if (have_view_) lex_.fail(v, "a second 'v': an NFF file has one viewpoint");
        have_view_ = true;
        NffView view;
        Token from, at, up, angle, resolution, hither, first;
        const auto take = [&](Token& slot) {
            if (slot.line != 0)
                lex_.fail(lex_.peek(), "v: a second '" + std::string(lex_.peek().text) + "'");
            slot = lex_.next();
        };
        for (;;) {
            const std::string_view key = lex_.peek().text;
            if (key == "from") {
                take(from);
                view.from = vec("v from");
            } else if (key == "at") {
                take(at);
                view.at = vec("v at");
            } else if (key == "up") {
                take(up);
                view.up = vec("v up");
            } else if (key == "angle") {
                take(angle);
                view.angle = number("v angle", &first);
                if (!(view.angle > 0 && view.angle < 180))
                    lex_.fail(first, "v angle must be between 0 and 180 degrees, got '" +
                                         shown(first.text) + "'");
            } else if (key == "hither") {
                take(hither);
                number("v hither");
            } else if (key == "resolution") {
                take(resolution);
                constexpr long kMax = 1'000'000;  // rt checks its own, smaller, limits
                view.xres = static_cast<int>(count("v resolution x", 1, kMax, &first));
                view.yres = static_cast<int>(count("v resolution y", 1, kMax, &first));
            } else {
                break;
            }
        }
        const std::pair<const Token*, const char*> required[] = {{&from, "from"},
                                                                 {&at, "at"},
                                                                 {&up, "up"},
                                                                 {&angle, "angle"},
                                                                 {&resolution, "resolution"}};
        for (const auto& [token, key] : required)
            if (token->line == 0)
                lex_.fail(lex_.peek(), std::string("v: missing '") + key +
                                           "' (a viewpoint has from, at, up, angle, hither "
                                           "and resolution)");
        if (!(rt::length(view.at - view.from) > 0))
            lex_.fail(at, "v: 'at' must differ from 'from'");
        NffViewer viewer;
        try {
            viewer = nff_viewer(view);
        } catch (const std::invalid_argument& e) {
            lex_.fail(up, e.what());
        }
        out_.at(v.line);
        out_.word("102");
        out_.at(from.line);
        out_.vec(viewer.eye);
        out_.at(at.line);
        out_.vec(viewer.look_at);
        out_.at(angle.line);
        out_.vec(viewer.x);
        out_.vec(viewer.y);
        out_.at(resolution.line);
        out_.whole(static_cast<std::size_t>(view.xres));
        out_.whole(static_cast<std::size_t>(view.yres));
    }

    void background(const Token& b) {
        if (have_background_) lex_.fail(b, "a second 'b': a scene has one background");
        have_background_ = true;
        const Vec3 c = colour("b colour");
        out_.at(b.line);
        out_.word("115");
        out_.vec(c);
    }

    // Held until the end, where their number is known: each gets 1/sqrt(n) of its colour.
    void light(const Token& l) {
        if (lights_.size() == options_.max_lights)
            lex_.fail(l, "more than " + std::to_string(options_.max_lights) + " lights");
        Light light;
        light.line = l.line;
        light.position = vec("l position");
        if (looks_numeric(lex_.peek().text)) light.colour = colour("l colour");
        lights_.push_back(light);
    }

    // f red green blue Kd Ks Shine T index_of_refraction: rt's simple surface (100), made the
    // default (105) that every later object takes (106).
    void fill(const Token& f) {
        const Vec3 c = colour("f colour");
        const double kd = non_negative("f Kd");
        const double ks = non_negative("f Ks");
        const double shine = non_negative("f Shine");
        const double kt = non_negative("f T");
        Token ior_at;
        const double ior = number("f index of refraction", &ior_at);
        if (kt > 0 && !(ior > 0))
            lex_.fail(ior_at, "f index of refraction must be > 0 when T > 0, got '" +
                                  shown(ior_at.text) + "'");
        have_surface_ = true;
        out_.at(f.line);
        out_.word("105");
        out_.word("100");
        out_.vec(c);
        out_.number(ks);
        out_.number(shine);
        out_.number(kd);
        out_.number(kt);
        out_.number(ior);
    }

    void sphere(const Token& s) {
        require_surface(s);
        const Vec3 centre = vec("s centre");
        Token r_at;
        const double r = number("s radius", &r_at);
        if (r == 0) lex_.fail(r_at, "s radius must not be 0");
        out_.at(s.line);
        out_.word("1");
        out_.number(std::fabs(r));  // negative: seen from inside; rt's spheres have two sides
        out_.vec(centre);
        out_.word("106");
    }

    // c, base x y z r, apex x y z r: a cylinder (9) when the radii are equal, else rt's cone
    // (8) cut to the part between them. Negative radii (seen from inside) count as positive.
    void cone(const Token& c) {
        require_surface(c);
        Token base_at, apex_at, rb_at, ra_at;
        const Vec3 base = vec("c base", &base_at);
        double rb = number("c base radius", &rb_at);
        const Vec3 apex = vec("c apex", &apex_at);
        double ra = number("c apex radius", &ra_at);
        if ((rb < 0 || ra < 0) && (rb > 0 || ra > 0))
            lex_.fail(ra_at,
                      "c radii must have the same sign (both negative: seen from "
                      "inside)");
        rb = std::fabs(rb);
        ra = std::fabs(ra);
        if (rb == 0 && ra == 0) lex_.fail(ra_at, "c radii must not both be 0");
        if (!(rt::length(apex - base) > 0)) lex_.fail(apex_at, "c apex must differ from base");
        out_.at(c.line);
        if (rb != ra) {
            const NffCone k = nff_cone(base, rb, apex, ra);
            if (!(k.alpha > 0)) lex_.fail(ra_at, "c is too flat for rt's cone");
            // Radii too close for cos(half-angle) to differ from 1 make a cylinder.
            if (k.alpha < 1) {
                out_.word("8");
                out_.number(k.alpha);
                out_.number(k.start);
                out_.number(k.finish);
                out_.vec(k.apex);
                out_.vec(k.axis);
                out_.word("106");
                return;
            }
        }
        out_.word("9");
        out_.number(rb == ra ? rb : (rb + ra) / 2);
        out_.word("0");
        out_.word("1");
        out_.vec(base);
        out_.vec(apex - base);
        out_.word("106");
    }

    // p n, then n vertices: rt's polygon (11), streamed vertex by vertex.
    void polygon(const Token& p) {
        require_surface(p);
        Token n_at;
        const long n =
            count("p vertex count", 3, static_cast<long>(options_.max_polygon_vertices), &n_at);
        out_.at(p.line);
        out_.word("11");
        out_.whole(static_cast<std::size_t>(n));
        for (long i = 0; i < n; ++i) {
            Token at;
            const Vec3 v = vec({"p vertex", i + 1}, &at);
            out_.at(at.line);
            out_.vec(v);
        }
        out_.word("106");
    }

    // pp n, then n (vertex, normal): gathered, with the patches before and after it that
    // nothing else separates, into one smooth mesh (16), each patch fanned into triangles.
    void patch(const Token& pp) {
        require_surface(pp);
        Token n_at;
        const long n =
            count("pp vertex count", 3, static_cast<long>(options_.max_polygon_vertices), &n_at);
        const std::size_t count_n = static_cast<std::size_t>(n);
        if (!mesh_.empty() && mesh_.size() + count_n > options_.max_mesh_vertices) flush_mesh();
        if (mesh_.empty()) mesh_line_ = pp.line;
        for (long i = 0; i < n; ++i) {
            const Label which{"pp vertex", i + 1};
            MeshVertex v;
            Token at, normal_at;
            v.position = vec(which, &at);
            v.normal = vec({"pp vertex", i + 1, "normal"}, &normal_at);
            if (!(rt::length_squared(v.normal) > 0))
                lex_.fail(normal_at, which.text() + " normal must not be zero");
            v.line = at.line;
            mesh_.push_back(v);
        }
        patch_sizes_.push_back(static_cast<std::uint32_t>(n));
    }

    void flush_mesh() {
        if (mesh_.empty()) return;
        std::size_t triangles = 0;
        for (const std::uint32_t n : patch_sizes_) triangles += n - 2;
        out_.at(mesh_line_);
        out_.word("16");
        out_.whole(mesh_.size());
        out_.whole(triangles);
        for (const MeshVertex& v : mesh_) {
            out_.at(v.line);
            out_.vec(v.position);
            out_.vec(v.normal);
        }
        std::size_t first = 0;
        for (const std::uint32_t n : patch_sizes_) {
            for (std::uint32_t i = 1; i + 1 < n; ++i) {
                out_.whole(first);
                out_.whole(first + i);
                out_.whole(first + i + 1);
            }
            first += n;
        }
        out_.word("106");
        mesh_.clear();
        patch_sizes_.clear();
    }

    void finish(const Token& end) {
        flush_mesh();
        if (!have_view_) lex_.fail(end, "no 'v' viewpoint in the file; rt needs one");
        // The SPD's convention (its generators scale lights so for renderers that do not):
        // n lights share the white of one, each 1/sqrt(n) of it.
        const double scale =
            lights_.empty() ? 0 : 1 / std::sqrt(static_cast<double>(lights_.size()));
        for (const Light& l : lights_) {
            out_.at(l.line);
            out_.word("104");
            out_.vec(l.position);
            out_.vec(l.colour * scale);
        }
        out_.finish();
    }

    struct Light {
        long line = 0;
        Vec3 position;
        Vec3 colour{1, 1, 1};
    };
    struct MeshVertex {
        Vec3 position, normal;
        long line = 0;
    };

    Lexer lex_;
    Writer out_;
    const NffOptions& options_;
    bool have_view_ = false;
    bool have_background_ = false;
    bool have_surface_ = false;
    std::vector<Light> lights_;
    std::vector<MeshVertex> mesh_;
    std::vector<std::uint32_t> patch_sizes_;
    long mesh_line_ = 0;
};

}  // namespace

void translate_nff(std::istream& in, const std::string& name, std::ostream& out,
                   const NffOptions& options) {
    Translator(in, name, out, options).run();
}

void translate_nff_file(const std::string& path, std::ostream& out, const NffOptions& options) {
    if (path == "-") return translate_nff(std::cin, "<stdin>", out, options);
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw CompileError(path + ": is a directory, not a scene");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw CompileError(path + ": cannot open");
    translate_nff(in, path, out, options);
}

std::string translate_nff_file(const std::string& path, const NffOptions& options) {
    std::ostringstream out;
    translate_nff_file(path, out, options);
    return std::move(out).str();
}

}  // namespace rtpp
