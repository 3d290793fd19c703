// The functions each primitive's source file provides, for the table in table.cpp.
// Each namespace is one primitive; its data structure stays private to its own file.
#pragma once

#include "rt/primitive.h"

namespace rt::sphere {
ReadShapeFn read;
IntersectFn intersect;
NormalFn normal;
BoundsFn bounds;
InsideFn inside;
}  // namespace rt::sphere

namespace rt::plane {
ReadShapeFn read;
IntersectFn intersect;
NormalFn normal;
BoundsFn bounds;
InsideFn inside;
}  // namespace rt::plane

namespace rt::disk {
ReadShapeFn read;
IntersectFn intersect;
NormalFn normal;
BoundsFn bounds;
}  // namespace rt::disk

namespace rt::annulus {
ReadShapeFn read;
IntersectFn intersect;
NormalFn normal;
BoundsFn bounds;
}  // namespace rt::annulus

namespace rt::triangle {
ReadShapeFn read;
IntersectFn intersect;
NormalFn normal;
BoundsFn bounds;
}  // namespace rt::triangle

namespace rt::parallelogram {
ReadShapeFn read;
IntersectFn intersect;
NormalFn normal;
BoundsFn bounds;
}  // namespace rt::parallelogram

namespace rt::affine {
ReadShapeFn read;
IntersectFn intersect;
IntersectFn intersect_any;
NormalFn normal;
BoundsFn bounds;
InsideFn inside;
PropertyFn has_inside;
PropertyFn carries_surfaces;
CollectFn collect;
BoundsFn solid_bounds;
}  // namespace rt::affine

namespace rt::cone {
ReadShapeFn read;
IntersectFn intersect;
NormalFn normal;
BoundsFn bounds;
}  // namespace rt::cone

namespace rt::cylinder {
ReadShapeFn read;
IntersectFn intersect;
NormalFn normal;
BoundsFn bounds;
}  // namespace rt::cylinder

namespace rt::torus {
ReadShapeFn read;
IntersectFn intersect;
NormalFn normal;
BoundsFn bounds;
InsideFn inside;
}  // namespace rt::torus

namespace rt::polygon {
ReadShapeFn read;
IntersectFn intersect;
NormalFn normal;
BoundsFn bounds;
}  // namespace rt::polygon

namespace rt::box {
ReadShapeFn read;
IntersectFn intersect;
NormalFn normal;
BoundsFn bounds;
InsideFn inside;
}  // namespace rt::box

namespace rt::quadric {
ReadShapeFn read;
IntersectFn intersect;
NormalFn normal;
BoundsFn bounds;
InsideFn inside;
CrossFn cross;
BoundsFn solid_bounds;
}  // namespace rt::quadric

namespace rt::mesh {
ReadShapeFn read;
IntersectFn intersect;
IntersectFn intersect_any;
NormalFn normal;
BoundsFn bounds;
}  // namespace rt::mesh

namespace rt::csg {
ReadShapeFn read_union;
ReadShapeFn read_intersection;
ReadShapeFn read_difference;
IntersectFn intersect;
NormalFn normal;
BoundsFn bounds;
BoundsFn solid_bounds;
InsideFn inside;
PropertyFn carries_surfaces;
CollectFn collect;
}  // namespace rt::csg
