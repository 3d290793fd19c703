// The table of primitive types. Adding a primitive is its source file, its declarations in
// primitives.h and one row here.
#include "id_table.h"
#include "primitives/primitives.h"

namespace rt {

namespace {

constexpr std::array kPrimitiveTypes{
    PrimitiveType{1, "sphere", sphere::read, sphere::intersect, sphere::normal, sphere::bounds,
                  sphere::inside},
    PrimitiveType{2, "plane", plane::read, plane::intersect, plane::normal, plane::bounds,
                  plane::inside},
    PrimitiveType{3, "disk", disk::read, disk::intersect, disk::normal, disk::bounds, nullptr},
    PrimitiveType{4, "annulus", annulus::read, annulus::intersect, annulus::normal, annulus::bounds,
                  nullptr},
    PrimitiveType{5, "triangle", triangle::read, triangle::intersect, triangle::normal,
                  triangle::bounds, nullptr},
    PrimitiveType{6, "parallelogram", parallelogram::read, parallelogram::intersect,
                  parallelogram::normal, parallelogram::bounds, nullptr},
    // Solid exactly when its inner primitive is, so it says so per instance.
    PrimitiveType{7, "affine", affine::read, affine::intersect, affine::normal, affine::bounds,
                  affine::inside, affine::has_inside},
    PrimitiveType{8, "cone", cone::read, cone::intersect, cone::normal, cone::bounds, nullptr},
    PrimitiveType{9, "cylinder", cylinder::read, cylinder::intersect, cylinder::normal,
                  cylinder::bounds, nullptr},
    PrimitiveType{10, "torus", torus::read, torus::intersect, torus::normal, torus::bounds,
                  torus::inside},
    PrimitiveType{11, "polygon", polygon::read, polygon::intersect, polygon::normal,
                  polygon::bounds, nullptr},
    PrimitiveType{12, "box", box::read, box::intersect, box::normal, box::bounds, box::inside},
    PrimitiveType{14, "mesh", mesh::read, mesh::intersect, mesh::normal, mesh::bounds, nullptr},
};

static_assert(strictly_sorted_by_id(kPrimitiveTypes), "rows sorted by ID, each ID once");

}  // namespace

std::span<const PrimitiveType> primitive_types() { return kPrimitiveTypes; }

const PrimitiveType* find_primitive_type(int id) { return find_by_id(kPrimitiveTypes, id); }

}  // namespace rt
