// Mesh from a file (ID 15): a mode, a path to a PLY or OBJ file, one surface for the whole.
// The file is found, read once and checked by the scene reader (SceneReader::mesh_file and
// the readers in src/scene/mesh_file.h); its triangles then behave as the mesh (14) where
// they are flat and as the smooth mesh (16) where they carry vertex normals:
// - mode 0: the file's vertex normals where it gives them, flat where it does not;
// - mode 1: flat always;
// - mode 2: the file's vertex normals, and angle-weighted ones computed from the faces for
//   the vertices it gives none (or a zero one).
// A triangle with a corner whose normal is zero (a PLY may give one, an OBJ corner without a
// normal has one; a computed normal is zero where its faces cancel) is flat.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "primitives/mesh_core.h"
#include "rt/error.h"
#include "rt/primitive.h"
#include "rt/reader.h"
#include "scene/mesh_file.h"

namespace rt::file_mesh {

namespace {

enum Mode : long { kFileNormals = 0, kFlat = 1, kSmooth = 2 };

std::string place(const char* what, std::size_t index) {
    return std::string(what) + " " + std::to_string(index);
}

// A file's normals are used as written, as a smooth mesh's (16) are, so that the same mesh
// written either way shades alike; each must be zero (flat there) or have a squared length
// that is a normal double, so that no blend of three overflows.
void check_normals(const std::vector<Vec3>& normals) {
    for (std::size_t i = 0; i < normals.size(); ++i) {
        if (normals[i] == Vec3{}) continue;
        const double squared = length_squared(normals[i]);
        if (!(squared >= std::numeric_limits<double>::min()) || !std::isfinite(squared))
            throw Error(place("vertex", i) +
                        ": its normal is too short or too long (its squared length must be "
                        "between about 1e-307 and 1e308, or zero for none)");
    }
}

FileMeshShape make(const MeshFile& file, long mode, int threads) {
    mesh_core::ShadedMesh mesh;  // normals: one per vertex, or none (flat)
    for (std::size_t i = 0; i < file.positions.size(); ++i)
        if (max_abs_component(file.positions[i]) > mesh_core::kMaxCoordinate)
            throw Error(place("vertex", i) + ": a coordinate is beyond +-" +
                        format_number(mesh_core::kMaxCoordinate));
    if (file.triangles.empty()) throw Error("it has no faces");
    mesh.core.vertices.assign(file.positions.begin(), file.positions.end());
    FileMeshShape made;
    made.skipped =
        mesh_core::build(mesh.core, static_cast<long>(file.triangles.size()), threads,
                         [&](long i) { return file.triangles[static_cast<std::size_t>(i)]; });
    if (mesh.core.triangles.empty())
        throw Error("it has no triangle with non-zero area (all " +
                    std::to_string(file.triangles.size()) + " are degenerate)");
    made.kept = mesh.core.triangles.size();
    if (mode != kFlat) {
        mesh.normals = file.normals;
        check_normals(mesh.normals);
        // Mode 2 computes the normals the file does not give: all of them, or those of the
        // vertices whose normal it gives as zero (OBJ corners without one).
        if (mode == kSmooth) {
            const bool some_missing =
                mesh.normals.empty() ||
                std::find(mesh.normals.begin(), mesh.normals.end(), Vec3{}) != mesh.normals.end();
            if (some_missing) {
                const std::vector<Vec3> computed =
                    angle_weighted_normals(file.positions, file.triangles);
                if (mesh.normals.empty()) mesh.normals.assign(computed.size(), Vec3{});
                for (std::size_t i = 0; i < computed.size(); ++i)
                    if (mesh.normals[i] == Vec3{}) mesh.normals[i] = computed[i];
            }
        }
    }
    made.shape = std::make_shared<const mesh_core::ShadedMesh>(std::move(mesh));
    return made;
}

ShapeData read(SceneReader& reader) {
    const long mode = reader.whole("mesh file mode (0, 1 or 2)", kFileNormals, kSmooth);
    const int threads = reader.threads();
    return reader.mesh_file(
        "mesh file path", static_cast<int>(mode),
        [mode, threads](const MeshFile& file) { return make(file, mode, threads); });
}

}  // namespace

// Everything but reading is the shaded mesh's (mesh_core.h), shared with the smooth mesh (16).
extern const PrimitiveFunctions functions = mesh_core::shaded::functions_with(read);

}  // namespace rt::file_mesh
