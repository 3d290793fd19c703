// The table of primitive types. Adding a primitive is its source file, which defines
// NAME::functions at its end, and two lines here: its declaration and its row.
#include <cmath>

#include "primitives/flat_corners.h"
#include "rt/primitive.h"
#include "scene/id_table.h"

namespace rt {

// Each is defined at the end of its primitive's source file; one line each, beside the rows.
// clang-format off
namespace sphere { extern const PrimitiveFunctions functions; }
namespace plane { extern const PrimitiveFunctions functions; }
namespace disk { extern const PrimitiveFunctions functions; }
namespace annulus { extern const PrimitiveFunctions functions; }
namespace triangle { extern const PrimitiveFunctions functions; }
namespace parallelogram { extern const PrimitiveFunctions functions; }
namespace affine { extern const PrimitiveFunctions functions; }
namespace cone { extern const PrimitiveFunctions functions; }
namespace cylinder { extern const PrimitiveFunctions functions; }
namespace torus { extern const PrimitiveFunctions functions; }
namespace polygon { extern const PrimitiveFunctions functions; }
namespace box { extern const PrimitiveFunctions functions; }
namespace quadric { extern const PrimitiveFunctions functions; }
namespace mesh { extern const PrimitiveFunctions functions; }
namespace file_mesh { extern const PrimitiveFunctions functions; }
namespace smooth_mesh { extern const PrimitiveFunctions functions; }
namespace csg { extern const PrimitiveFunctions union_functions; }
namespace csg { extern const PrimitiveFunctions intersection_functions; }
namespace csg { extern const PrimitiveFunctions difference_functions; }
// clang-format on

namespace {

constexpr std::array kPrimitiveTypes{
    PrimitiveType{1, "sphere", &sphere::functions},
    PrimitiveType{2, "plane", &plane::functions},
    PrimitiveType{3, "disk", &disk::functions},
    PrimitiveType{4, "annulus", &annulus::functions},
    PrimitiveType{5, "triangle", &triangle::functions},
    PrimitiveType{6, "parallelogram", &parallelogram::functions},
    PrimitiveType{7, "affine", &affine::functions},
    PrimitiveType{8, "cone", &cone::functions},
    PrimitiveType{9, "cylinder", &cylinder::functions},
    PrimitiveType{10, "torus", &torus::functions},
    PrimitiveType{11, "polygon", &polygon::functions},
    PrimitiveType{12, "box", &box::functions},
    PrimitiveType{13, "quadric", &quadric::functions},
    PrimitiveType{14, "mesh", &mesh::functions},
    PrimitiveType{15, "mesh from a file", &file_mesh::functions},
    PrimitiveType{16, "smooth mesh", &smooth_mesh::functions},
    PrimitiveType{20, "union", &csg::union_functions},
    PrimitiveType{21, "intersection", &csg::intersection_functions},
    PrimitiveType{22, "difference", &csg::difference_functions},
};

static_assert(strictly_sorted_by_id(kPrimitiveTypes), "rows sorted by ID, each ID once");

}  // namespace

std::span<const PrimitiveType> primitive_types() { return kPrimitiveTypes; }

const PrimitiveType* find_primitive_type(int id) { return find_by_id(kPrimitiveTypes, id); }

bool Shape::cross(const Ray& ray, Interval range, Crossing& crossing) const {
    if (functions->cross != nullptr) return functions->cross(data.get(), ray, range, crossing);
    // Every crossing of an ordinary solid is a visible hit; the outward normal says which way.
    Hit hit;
    if (!intersect(ray, range, hit)) return false;
    crossing.hit = hit;
    crossing.entering = dot(normal(ray.at(hit.t), hit), ray.direction) < 0;
    crossing.visible = true;
    return true;
}

namespace {
// A simple solid's boundary meets a line a few times at most (a torus four); the cap only
// guards against a crossing routine that fails to move on.
constexpr int kMaxSimpleCrossings = 16;
}  // namespace

double step_past(double t) {
    return std::max(std::nextafter(t, kInfinity), t + std::fabs(t) * kCrossingStep);
}

bool Shape::collect(const Ray& ray, double t_min, Crossings& out) const {
    if (functions->collect != nullptr) return functions->collect(data.get(), ray, t_min, out);
    // A simple solid: step from one crossing to the next.
    Crossing crossing;
    double from = t_min;
    bool started_inside = false;
    bool inside_now = false;
    for (int i = 0; i < kMaxSimpleCrossings && cross(ray, {from, kInfinity}, crossing); ++i) {
        // A crossing must lie past the last: one that does not (NaN, from arithmetic that
        // overflowed or a ray with no direction) cannot be placed on the ray, and would stall
        // a composite's merge.
        if (!(crossing.hit.t > from)) break;
        if (i == 0) started_inside = inside_now = !crossing.entering;
        // A crossing that does not change sides (a tangent touch) changes nothing.
        if (crossing.entering != inside_now) {
            out.push_back(crossing);
            inside_now = crossing.entering;
        }
        from = step_past(crossing.hit.t);
    }
    if (from != t_min) return started_inside;
    // No crossing at all: the whole ray is on one side, so ask at a point well along it,
    // away from any surface the ray may start on.
    return inside(ray.at(2 * t_min + 1));
}

std::vector<Vec3> flat_corners(const Shape& shape) {
    if (shape.functions->corners == nullptr) return {};
    return shape.functions->corners(shape.data.get());
}

}  // namespace rt
