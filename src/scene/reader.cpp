// The field readers: the numbers, vectors and paths the object tables' read functions ask
// for, each checked and reported at its place in the file.
#include "rt/reader.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "rt/error.h"
#include "scene/lexer.h"
#include "scene/mesh_file.h"
#include "scene/texture.h"

namespace rt {

SceneReader::SceneReader(std::istream& in, std::string name, std::filesystem::path base_dir,
                         int threads)
    : lexer_(std::make_unique<Lexer>(in, std::move(name))),
      textures_(std::make_unique<TextureCache>()),
      mesh_files_(std::make_unique<MeshFileCache>()),
      base_dir_(std::move(base_dir)),
      threads_(threads) {}

SceneReader::~SceneReader() = default;

Location SceneReader::next_location() { return lexer_->peek().where; }

std::size_t SceneReader::textures_loaded() const { return textures_->files(); }

std::size_t SceneReader::mesh_files_read() const { return mesh_files_->files(); }

// Every spelling is a dependency: a symbolic link among them can later be pointed at another
// file.
void SceneReader::add_input(const std::filesystem::path& resolved, const char* role) {
    for (const SceneInput& known : inputs_)
        if (known.path == resolved) return;
    inputs_.push_back({resolved, role});
}

void SceneReader::fail(Location where, std::string_view message) const {
    lexer_->fail(where, message);
}

std::filesystem::path SceneReader::resolve(const std::string& path) const {
    const std::filesystem::path p(path);
    return p.is_absolute() || base_dir_.empty() ? p : base_dir_ / p;
}

SceneReader::Nest::Nest(SceneReader& reader, Location where) : reader_(reader) {
    if (reader_.depth_ >= kMaxNesting)
        reader_.fail(where, "objects nested more than " + std::to_string(kMaxNesting) +
                                " deep (affine, checker and image-mapped objects count)");
    ++reader_.depth_;
}

bool SceneReader::plain_number(double& value) {
    // A plain decimal is short: its text is kept in a small buffer, without the string's calls.
    static_assert(sizeof last_plain_text_ == kDecimalReadable);
    if (!lexer_->next_decimal(value, last_number_, last_plain_text_, last_plain_size_))
        return false;
    ++numbers_read_;
    return true;
}

double SceneReader::number(std::string_view what) {
    // plain_number, spelled out so that the lexer's common case compiles into this function.
    double value = 0;
    if (lexer_->next_decimal(value, last_number_, last_plain_text_, last_plain_size_)) {
        ++numbers_read_;
        return value;
    }
    return written_number(what);
}

// Any other token, out of line so that number() stays small.
[[gnu::noinline]] double SceneReader::written_number(std::string_view what) {
    double value = 0;
    const Token& token = lexer_->next();
    if (token.at_end()) fail(token.where, "unexpected end of file: expected " + std::string(what));
    ++numbers_read_;
    last_number_ = token.where;
    last_number_text_ = token.text;
    last_plain_size_ = 0;
    if (token.quoted)
        fail(token.where, "expected " + std::string(what) + " (a number), got a quoted string");
    // strtod decides what a number is. from_chars reads the plain decimal numbers that scenes
    // are made of several times faster and, for a token it reads completely, gives the value
    // strtod gives (both round correctly); anything else (a leading '+', hexadecimal, a
    // number out of range, not a number at all) goes to strtod, which reads the copy (it
    // needs the terminating NUL).
    const char* begin = last_number_text_.c_str();
    const char* end = begin + last_number_text_.size();
    if (const auto [stop, error] = std::from_chars(begin, end, value);
        error != std::errc{} || stop != end) {
        char* strtod_end = nullptr;
        value = std::strtod(begin, &strtod_end);
        if (strtod_end == begin || *strtod_end != '\0')
            fail(token.where,
                 "expected " + std::string(what) + " (a number), got " + quote_token(token.text));
    }
    if (!std::isfinite(value))
        fail(token.where,
             std::string(what) + " must be a finite number, got " + quote_token(token.text));
    return value;
}

double SceneReader::positive(std::string_view what) {
    const Location where = next_location();
    const double value = number(what);
    if (!(value > 0)) fail(where, std::string(what) + " must be > 0, got " + last_number_text());
    return value;
}

double SceneReader::non_negative(std::string_view what) {
    const Location where = next_location();
    const double value = number(what);
    if (!(value >= 0)) fail(where, std::string(what) + " must be >= 0, got " + last_number_text());
    return value;
}

Vec3 SceneReader::vec3(std::string_view what) {
    const double x = number(what);
    const double y = number(what);
    const double z = number(what);
    return {x, y, z};
}

std::string SceneReader::last_number_text() const {
    return show_token(last_plain_size_ > 0 ? std::string_view(last_plain_text_, last_plain_size_)
                                           : std::string_view(last_number_text_));
}

Vec3 SceneReader::nonzero_vec3(std::string_view what) {
    const Location where = next_location();
    const Vec3 v = vec3(what);
    if (!(max_abs_component(v) > 0))
        fail(where, std::string(what) + " must have a non-zero, finite length");
    // Its length is used as it is, squared, so the square must be a normal number.
    const double squared = length_squared(v);
    if (!(squared >= std::numeric_limits<double>::min()) || !std::isfinite(squared))
        fail(where, std::string(what) +
                        " is too short or too long: its squared length must be between about "
                        "1e-307 and 1e308");
    return v;
}

Vec3 SceneReader::direction(std::string_view what, double* length_out) {
    const Location where = next_location();
    const Vec3 v = vec3(what);
    // Dividing by the largest absolute component before squaring keeps a squared length from
    // underflowing (or overflowing) for any finite, non-zero vector.
    const double largest = max_abs_component(v);
    if (!(largest > 0)) fail(where, std::string(what) + " must have a non-zero length");
    // Scaled only when the squared length leaves the normal doubles, so that every other
    // direction comes out exactly as v / |v| always did.
    const double squared = length_squared(v);
    const bool normal = squared >= std::numeric_limits<double>::min() && std::isfinite(squared);
    const double scale = normal ? 1 : largest;
    const Vec3 scaled = v / scale;
    const double scaled_length = length(scaled);
    if (length_out != nullptr) *length_out = scale * scaled_length;
    return scaled / scaled_length;
}

long SceneReader::whole(std::string_view what, long min, long max) {
    const Location where = next_location();
    const double value = number(what);
    if (value != std::floor(value))
        fail(where, std::string(what) + " must be a whole number, got " + last_number_text());
    if (value < static_cast<double>(min) || value > static_cast<double>(max))
        fail(where, std::string(what) + " must be between " + std::to_string(min) + " and " +
                        std::to_string(max) + ", got " + last_number_text());
    return static_cast<long>(value);
}

long SceneReader::id(std::string_view what) {
    const Location where = next_location();
    const double value = number(what);
    if (value != std::floor(value))
        fail(where, std::string(what) + " must be a whole number, got " + last_number_text());
    // No ID is near this; the bound only keeps the conversion to long defined.
    if (std::fabs(value) > 1e9)
        fail(where, std::string(what) + " is out of range (no ID is beyond 1e9), got " +
                        last_number_text());
    return static_cast<long>(value);
}

std::string SceneReader::path(std::string_view what) {
    const Token& token = lexer_->next();
    if (token.at_end()) fail(token.where, "unexpected end of file: expected " + std::string(what));
    if (token.text.empty()) fail(token.where, std::string(what) + " must not be empty");
    return std::string(token.text);
}

namespace {
// Why a file a scene names could not be used, for fail(): paths are shown whole (escaped), as
// a user needs all of one to find the file.
std::string cannot_read(std::string_view what, const std::string& written,
                        const std::filesystem::path& resolved, const char* reason) {
    std::string message = "cannot read " + std::string(what) + " " +
                          quote_token(written, kMaxTokenLength) + ": " + reason;
    if (resolved.string() != written)
        message += " (looked for " + quote_token(resolved.string(), kShowWhole) + ")";
    return message;
}
}  // namespace

std::shared_ptr<const Image> SceneReader::texture(std::string_view what) {
    const Location where = next_location();
    const std::string written = path(what);
    const std::filesystem::path resolved = resolve(written);
    add_input(resolved, "the texture");
    try {
        return textures_->load(resolved);
    } catch (const Error& e) {
        fail(where, cannot_read("texture", written, resolved, e.what()));
    }
}

ShapeData SceneReader::mesh_file(std::string_view what, int mode, const MakeFileMesh& make) {
    const Location where = next_location();
    const std::string written = path(what);
    const std::filesystem::path resolved = resolve(written);
    add_input(resolved, "the mesh file");
    try {
        MeshFileCache::Entry& entry = mesh_files_->load(resolved, notes_);
        auto& made = entry.shapes[static_cast<std::size_t>(mode)];
        if (!made) made = make(entry.file);
        count_mesh_triangles(made->kept, made->skipped);
        return made->shape;
    } catch (const Error& e) {
        fail(where, cannot_read("mesh file", written, resolved, e.what()));
    }
}

}  // namespace rt
