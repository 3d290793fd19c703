// The corners of flat primitives, for a tool that hands them to another library as triangles
// (bench/embree) and confirms every candidate with the primitive's own test.
#pragma once

#include <vector>

#include "rt/primitive.h"

namespace rt {

// A polygon's (11) outline lifted back onto its plane (where its test hits it), or a
// triangle's (5) three vertices; empty for every other type. The fan of triangles from the
// first corner covers every point the primitive's own test hits, whatever the outline
// (concave, or crossing itself): such a point has a winding number other than zero, and the
// fan's triangles, counted with their orientation, add up to it.
// From the table's corners column (PrimitiveFunctions::corners).
std::vector<Vec3> flat_corners(const Shape& shape);

}  // namespace rt
