// A scene as the reader returns it: a value with no ties to global state.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rt/large_pages.h"
#include "rt/light.h"
#include "rt/primitive.h"
#include "rt/surface.h"
#include "rt/viewer.h"

namespace rt {

// The hierarchy over a scene's objects (src/accel/object_index.h): the renderer's own business.
class ObjectIndex;

// The object that last blocked a shadow ray toward one light, as the hierarchy names it.
// Neighbouring points are mostly shadowed by the same object, so it is tried first; a shadow
// ray that nothing blocks forgets it, unless it is a sphere (ObjectIndex::any).
struct LastBlocker {
    std::uint32_t entry = 0xffffffff;  // none yet
};

// A primitive placed in the scene with its surface.
struct Object {
    Shape shape;
    SurfacePtr surface;  // nullptr when the shape carries its operands' surfaces (CSG)

    // The surface at a hit on this object: the operand's where a composite reports one.
    const Surface& surface_at(const Hit& hit) const {
        return hit.surface != nullptr ? *hit.surface : *surface;
    }
};

struct Scene {
    Viewer viewer;
    // In 2 MiB pages once it is large (rt/large_pages.h): a million objects are 48 MB,
    // written, and moved each time the vector grows, as they are read.
    std::vector<Object, LargeArrayAllocator<Object>> objects;
    std::vector<Light> lights;
    Spectrum ambient{0.0};  // the sum of the ambient lights (ID 103)
    // What a ray that hits nothing brings back (ID 115); without it, the ambient intensity.
    std::optional<Spectrum> background;
    // The hierarchy over `objects`, once build_index() has run; shared by copies of the scene.
    std::shared_ptr<const ObjectIndex> index;
    // Zero-area triangles that meshes left out (they are accepted, not errors).
    std::size_t skipped_triangles = 0;
    // The triangles the meshes hold, each placement of a mesh counted: with the objects, how
    // many primitives a ray may have to test (where no box can tell them apart, all of them).
    std::size_t mesh_triangles = 0;
    // What the reader accepted but ignored (a mesh file's texture coordinates, say), one
    // sentence each naming its file, for rt to show as notes.
    std::vector<std::string> notes;
    // Whether some surface can send both a mirror ray and a refracted ray from one hit (glass,
    // or ks and kt both above 0): only then can the rays of a pixel grow exponentially with -d.
    bool splits_rays = false;

    // Builds the hierarchy over the objects on up to `threads` threads (the same hierarchy
    // for any number); read_scene() and read_scene_file() call it.
    void build_index(int threads = 1);
};

}  // namespace rt
