// The table of primitive types. Adding a primitive is its source file, its declarations in
// primitives.h and one row here. Columns left out of a row are nullptr (see primitive.h).
#include <cmath>

#include "scene/id_table.h"
#include "primitives/primitives.h"

namespace rt {

namespace {

constexpr std::array kPrimitiveTypes{
    PrimitiveType{.id = 1, .name = "sphere", .read = sphere::read, .intersect = sphere::intersect,
                  .normal = sphere::normal, .bounds = sphere::bounds, .inside = sphere::inside},
    PrimitiveType{.id = 2, .name = "plane", .read = plane::read, .intersect = plane::intersect,
                  .normal = plane::normal, .bounds = plane::bounds, .inside = plane::inside},
    PrimitiveType{.id = 3, .name = "disk", .read = disk::read, .intersect = disk::intersect,
                  .normal = disk::normal, .bounds = disk::bounds},
    PrimitiveType{.id = 4, .name = "annulus", .read = annulus::read,
                  .intersect = annulus::intersect, .normal = annulus::normal,
                  .bounds = annulus::bounds},
    PrimitiveType{.id = 5, .name = "triangle", .read = triangle::read,
                  .intersect = triangle::intersect, .normal = triangle::normal,
                  .bounds = triangle::bounds},
    PrimitiveType{.id = 6, .name = "parallelogram", .read = parallelogram::read,
                  .intersect = parallelogram::intersect, .normal = parallelogram::normal,
                  .bounds = parallelogram::bounds},
    // Solid, and carrying surfaces, exactly when its inner primitive is, so it says so per
    // instance; it forwards everything else to the inner primitive too.
    PrimitiveType{.id = 7, .name = "affine", .read = affine::read, .intersect = affine::intersect,
                  .normal = affine::normal, .bounds = affine::bounds, .inside = affine::inside,
                  .has_inside = affine::has_inside, .intersect_any = affine::intersect_any,
                  .carries_surfaces = affine::carries_surfaces, .collect = affine::collect,
                  .solid_bounds = affine::solid_bounds},
    PrimitiveType{.id = 8, .name = "cone", .read = cone::read, .intersect = cone::intersect,
                  .normal = cone::normal, .bounds = cone::bounds},
    PrimitiveType{.id = 9, .name = "cylinder", .read = cylinder::read,
                  .intersect = cylinder::intersect, .normal = cylinder::normal,
                  .bounds = cylinder::bounds},
    PrimitiveType{.id = 10, .name = "torus", .read = torus::read, .intersect = torus::intersect,
                  .normal = torus::normal, .bounds = torus::bounds, .inside = torus::inside},
    PrimitiveType{.id = 11, .name = "polygon", .read = polygon::read,
                  .intersect = polygon::intersect, .normal = polygon::normal,
                  .bounds = polygon::bounds},
    PrimitiveType{.id = 12, .name = "box", .read = box::read, .intersect = box::intersect,
                  .normal = box::normal, .bounds = box::bounds, .inside = box::inside},
    // Its solid f < 0 is not clipped by its box, so it reports invisible crossings too.
    PrimitiveType{.id = 13, .name = "quadric", .read = quadric::read,
                  .intersect = quadric::intersect, .normal = quadric::normal,
                  .bounds = quadric::bounds, .inside = quadric::inside, .cross = quadric::cross,
                  .solid_bounds = quadric::solid_bounds},
    // A shadow ray stops at the first triangle it meets.
    PrimitiveType{.id = 14, .name = "mesh", .read = mesh::read, .intersect = mesh::intersect,
                  .normal = mesh::normal, .bounds = mesh::bounds,
                  .intersect_any = mesh::intersect_any},
    // Composites: their operands bring their own surfaces, and the boundary is found from
    // the operands' crossings.
    PrimitiveType{.id = 20, .name = "union", .read = csg::read_union, .intersect = csg::intersect,
                  .normal = csg::normal, .bounds = csg::bounds, .inside = csg::inside,
                  .carries_surfaces = csg::carries_surfaces, .collect = csg::collect,
                  .solid_bounds = csg::solid_bounds},
    PrimitiveType{.id = 21, .name = "intersection", .read = csg::read_intersection,
                  .intersect = csg::intersect, .normal = csg::normal, .bounds = csg::bounds,
                  .inside = csg::inside, .carries_surfaces = csg::carries_surfaces,
                  .collect = csg::collect, .solid_bounds = csg::solid_bounds},
    PrimitiveType{.id = 22, .name = "difference", .read = csg::read_difference,
                  .intersect = csg::intersect, .normal = csg::normal, .bounds = csg::bounds,
                  .inside = csg::inside, .carries_surfaces = csg::carries_surfaces,
                  .collect = csg::collect, .solid_bounds = csg::solid_bounds},
};

static_assert(strictly_sorted_by_id(kPrimitiveTypes), "rows sorted by ID, each ID once");

}  // namespace

std::span<const PrimitiveType> primitive_types() { return kPrimitiveTypes; }

const PrimitiveType* find_primitive_type(int id) { return find_by_id(kPrimitiveTypes, id); }

bool Shape::cross(const Ray& ray, Interval range, Crossing& crossing) const {
    if (type->cross != nullptr) return type->cross(data.get(), ray, range, crossing);
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
    if (type->collect != nullptr) return type->collect(data.get(), ray, t_min, out);
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

}  // namespace rt
