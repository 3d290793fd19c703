// The table of surface types (the IDs allowed in a primitive's surface slot, except 106,
// which the reader resolves to the current default).
#include "scene/id_table.h"
#include "surfaces/surfaces.h"

namespace rt {

namespace {

constexpr std::array kSurfaceTypes{
    SurfaceType{100, "simple surface", simple_surface::read, simple_surface::evaluate},
    SurfaceType{107, "checker surface", checker_surface::read, checker_surface::evaluate},
    SurfaceType{108, "image-mapped surface", image_surface::read, image_surface::evaluate},
    SurfaceType{111, "affine surface", affine_surface::read, affine_surface::evaluate},
    SurfaceType{114, "glass surface", glass_surface::read, simple_surface::evaluate},
};

static_assert(strictly_sorted_by_id(kSurfaceTypes), "rows sorted by ID, each ID once");

}  // namespace

std::span<const SurfaceType> surface_types() { return kSurfaceTypes; }

const SurfaceType* find_surface_type(int id) { return find_by_id(kSurfaceTypes, id); }

}  // namespace rt
