// Triangle meshes read from PLY and Wavefront OBJ files (the mesh from a file, ID 15): the
// parsers work on the file's bytes in memory, so the caller opens the file (safely, as a
// texture) and keeps the place a message names. Every error is an rt::Error whose message
// starts with the file's display name and the place: "name:line:col: " for OBJ and for PLY
// headers and ASCII bodies, "name: vertex 12, byte 345: " for PLY binary bodies.
#pragma once

#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rt/reader.h"
#include "rt/vec.h"
#include "scene/input_file.h"

namespace rt {

// What a mesh file holds, as rt uses it: one position per vertex, optionally one normal per
// vertex (as the file gives it: not necessarily unit, possibly zero), and triangles of
// zero-based vertex indices, each below positions.size(). Polygons are fan-triangulated:
// v0 v1 ... v(n-1) becomes (v0, v1, v2), (v0, v2, v3), ..., (v0, v(n-2), v(n-1)).
// Triangles with a repeated index or zero area are kept (the mesh primitive skips them).
struct MeshFile {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;  // empty, or one per position
    std::vector<std::array<std::uint32_t, 3>> triangles;
    // What the file held that rt read and ignored, one short sentence per kind, in the order
    // first met (for the caller to show as notes).
    std::vector<std::string> notes;
};

// The most vertices (after any splitting for OBJ corner normals) and triangles a file may
// give: indices must fit a signed 32-bit integer.
inline constexpr std::uint64_t kMaxMeshElements = 2147483647;

// Whether the bytes are a PLY file: they start with the line "ply" (ended by LF, CRLF or CR).
bool is_ply(std::string_view bytes);

// Reads a PLY file if is_ply(bytes), else an OBJ file.
MeshFile read_mesh_file(std::string_view bytes, const std::string& display_name);

// PLY 1.0: ascii, binary_little_endian or binary_big_endian; element vertex with x, y, z and
// optionally nx, ny, nz (all three, or the normals are ignored); element face with a list
// vertex_indices (or vertex_index; the first such list is used). Faces of fewer than 3
// indices are skipped (and noted); other properties and elements are skipped whatever their
// type (and noted). Claimed counts are checked against the bytes after the header before
// anything is reserved. ASCII records are a stream of values (line breaks are not checked);
// ASCII values of type float keep the decimal as a double; integer values must fit their
// type. In a binary file end_header's line must end as the "ply" line does. Bytes after the
// last element are noted, not refused. Coordinates and normals must be finite.
MeshFile read_ply(std::string_view bytes, const std::string& display_name);

// Wavefront OBJ: v, vn and f (v, v/vt, v//vn, v/vt/vn; negative indices count back from the
// last vertex defined so far; an index must name a vertex or normal defined before its face).
// A position whose corners carry different normals becomes one vertex per distinct normal;
// when some face corners have a normal, the mesh has normals, and a corner without one has
// the zero normal (noted when only some corners have one).
// A face needs at least 3 corners. "#" starts a comment anywhere; a backslash at the end of a
// line continues it; a leading byte-order mark is skipped. Other statements of the OBJ
// format (vt, o, g, s, usemtl, mtllib, l, p, and free-form geometry) are ignored and noted
// once each; anything else is an error.
MeshFile read_obj(std::string_view bytes, const std::string& display_name);

// Angle-weighted vertex normals (mode 2 of ID 15): each triangle adds its unit face normal
// times its corner angle at each of its three vertices, and each sum is normalised. Zero-area
// triangles add nothing, so a vertex that no triangle of non-zero area touches (or whose
// contributions cancel) gets the zero vector: the caller shades its triangles flat. Indices
// must be below positions.size() (the readers guarantee it).
std::vector<Vec3> angle_weighted_normals(std::span<const Vec3> positions,
                                         std::span<const std::array<std::uint32_t, 3>> triangles);

// The mesh files one scene has read: each file once (by device and inode), however many
// objects name it, by whatever path; and the shapes made from it, one per mode of ID 15.
class MeshFileCache {
  public:
    struct Entry {
        MeshFile file;
        std::array<std::optional<FileMeshShape>, 3> shapes;  // by mode
    };
    // The file at `resolved`, read the first time its file is named, when its notes (each
    // prefixed with the path) are appended to `notes`. Throws rt::Error("<reason>"): the
    // file's own place comes first in a reader's message.
    Entry& load(const std::filesystem::path& resolved, std::vector<std::string>& notes);
    std::size_t files() const { return entries_.size(); }

  private:
    std::map<FileId, Entry> entries_;  // by file, not by name
};

// What the two readers share: places in text and tokens as messages show them.
namespace mesh_detail {

struct TextPlace {
    std::size_t line = 1;
    std::size_t column = 1;  // in bytes
};

// The line and column of a byte offset; a line ends at LF, CRLF or CR. Only messages need it,
// so the readers do not count lines as they go.
inline TextPlace text_place(std::string_view bytes, std::size_t offset) {
    TextPlace place;
    std::size_t line_start = 0;
    for (std::size_t i = 0; i < offset && i < bytes.size(); ++i) {
        if (bytes[i] == '\n' ||
            (bytes[i] == '\r' && (i + 1 >= bytes.size() || bytes[i + 1] != '\n'))) {
            ++place.line;
            line_start = i + 1;
        }
    }
    place.column = offset - line_start + 1;
    return place;
}

// A token quoted for a message: at most 40 bytes, and bytes outside printable ASCII as \xNN,
// so that a hostile file cannot put terminal escapes into a message.
inline std::string quoted_token(std::string_view token) {
    constexpr std::size_t kLongest = 40;
    static constexpr char kHex[] = "0123456789abcdef";
    std::string s = "'";
    for (std::size_t i = 0; i < token.size() && i < kLongest; ++i) {
        const auto c = static_cast<unsigned char>(token[i]);
        if (c >= 0x20 && c < 0x7f) {
            s += static_cast<char>(c);
        } else {
            s += "\\x";
            s += kHex[c >> 4];
            s += kHex[c & 15];
        }
    }
    if (token.size() > kLongest) s += "...";
    return s + "'";
}

// Parses a finite decimal number starting at p and returns its end, or nullptr when there is
// none or it is not finite. A leading '+' is accepted (from_chars refuses it; OBJ files have it).
inline const char* parse_finite(const char* p, const char* end, double& value) {
    if (p < end && *p == '+') {
        ++p;
        if (p == end || !((*p >= '0' && *p <= '9') || *p == '.')) return nullptr;
    }
    const std::from_chars_result r = std::from_chars(p, end, value);
    if (r.ec != std::errc() || !std::isfinite(value)) return nullptr;
    return r.ptr;
}

}  // namespace mesh_detail

}  // namespace rt
