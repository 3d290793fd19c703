// The table of primitive types: one row per ID, each with read, intersect and normal functions
// and the bounds and inside functions that bounding volumes and CSG need.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "rt/ray.h"

namespace rt {

class SceneReader;
struct Surface;
class WideRay;  // a ray prepared for the hierarchies' float box test (src/accel/bvh.h)

// What an intersect routine reports: the distance along the ray, and which part of a
// primitive made of several (the face of a box, say) was hit, so the normal can use it.
// Composites (CSG) also say which operand was hit and whose surface applies there.
struct Hit {
    double t = kInfinity;
    int part = 0;
    // For CSG: one bit per level, the innermost composite's choice (0: operand A, 1: B) in
    // the lowest bit; each enclosing composite shifts it left and adds its own.
    std::uint64_t path = 0;
    // The surface of the operand that was hit; nullptr means the object's own surface.
    const Surface* surface = nullptr;
};

// Where a ray crosses the boundary of a solid: the hit, whether the ray goes in or out
// there, and whether the crossing is on a visible surface. A quadric's solid f < 0 is not
// clipped by its box, so the ray can cross it where no surface is drawn; CSG needs those
// crossings to know which side it is on.
struct Crossing {
    Hit hit;
    bool entering = false;
    bool visible = true;
};

// Crossings along one ray in increasing t. CSG keeps one per thread as scratch space used
// like a stack (each composite appends its operands' lists, merges them, and drops them), so
// tracing allocates nothing once it has grown to the deepest composite.
using Crossings = std::vector<Crossing>;

// A primitive's parameters, owned here and seen only by the primitive's own source file.
using ShapeData = std::shared_ptr<const void>;

// Reads the primitive's numbers (after its ID) and returns its precomputed parameters.
using ReadShapeFn = ShapeData(SceneReader& reader);
// Finds the nearest hit with range.t_min < t < range.t_max along a ray whose direction is
// unit length. Returns false, leaving hit alone, when there is none.
using IntersectFn = bool(const void* shape, const Ray& ray, Interval range, Hit& hit);
// The unit outward normal at a point on the surface reported by intersect.
using NormalFn = Vec3(const void* shape, const Vec3& point, const Hit& hit);
// normal: what the primitive's NormalFn gives for the same point and hit, which the caller
// has already (a smooth mesh's blend turns to its face normal's side without computing it
// again).
using ShadingNormalFn = Vec3(const void* shape, const Vec3& point, const Hit& hit,
                             const Vec3& normal);
// A box that contains the whole primitive (infinite for unbounded ones).
using BoundsFn = Bounds(const void* shape);
// True when a point lies inside a solid primitive.
using InsideFn = bool(const void* shape, const Vec3& point);
// A property of one instance, for the few types where it depends on the parameters (an
// affine of a sphere has an inside, an affine of a disk does not).
using PropertyFn = bool(const void* shape);
// The nearest crossing of a solid's boundary with range.t_min < t < range.t_max, including
// crossings that are not visible. Returns false, leaving crossing alone, when there is none.
using CrossFn = bool(const void* shape, const Ray& ray, Interval range, Crossing& crossing);
// Appends every crossing of a solid's boundary with t > t_min, in increasing t, and returns
// whether the point at t_min (just past it) is inside the solid.
using CollectFn = bool(const void* shape, const Ray& ray, double t_min, Crossings& out);
// A flat primitive's corners (primitives/flat_corners.h).
using CornersFn = std::vector<Vec3>(const void* shape);
// intersect (or intersect_any), told the ray as the object hierarchy's walk prepared it for
// its float box test: WideRay(ray, range.t_min), or nullptr where the walk prepared none.
using PreparedIntersectFn = bool(const void* shape, const Ray& ray, Interval range, Hit& hit,
                                 const WideRay* prepared);
// A sphere's centre and squared radius (primitives/sphere_test.h).
struct SphereParameters {
    Vec3 centre;
    double radius_squared;
};
using SphereFn = SphereParameters(const void* shape);
// Boxes that together hold every part of a primitive with a hierarchy of its own, at most
// `at_most` of them unless its root alone has more (accel/bvh.h, Bvh::outline).
using OutlineFn = std::vector<Bounds>(const void* shape, std::size_t at_most);

// What a primitive does. Each primitive's source file defines one, at its end, from
// functions private to that file; the table in table.cpp gives it an ID and a name.
struct PrimitiveFunctions {
    ReadShapeFn* read;
    IntersectFn* intersect;
    NormalFn* normal;
    BoundsFn* bounds;
    InsideFn* inside = nullptr;  // nullptr where the primitive encloses no volume (disk, ...)
    // nullptr (the usual case) when every instance with an inside function has an inside.
    PropertyFn* has_inside = nullptr;
    // For shadow rays: true when any part of the primitive lies along the ray in range, with
    // `hit` left undefined, so a primitive made of many (a mesh) can stop at the first.
    // nullptr (the usual case) where intersect answers that as fast.
    IntersectFn* intersect_any = nullptr;
    // For solids whose boundary can be crossed where nothing is visible (the clipped
    // quadric, CSG). nullptr (the usual case): every crossing is an intersect hit, entering
    // where the outward normal faces the ray.
    CrossFn* cross = nullptr;
    // True when the primitive carries its operands' surfaces, so no surface follows it in the
    // scene (CSG, or an affine of CSG). nullptr: always false.
    PropertyFn* carries_surfaces = nullptr;
    // For composites (CSG) and frames around them: every crossing at once. nullptr (the usual
    // case): the crossings are found one after another with cross.
    CollectFn* collect = nullptr;
    // A box containing the solid (its inside), where that is not the box of the surface: a
    // quadric's solid is not clipped. nullptr: the same as bounds.
    BoundsFn* solid_bounds = nullptr;
    // The unit outward normal that shading uses (the Phong terms, the mirror and refracted
    // directions), where it is not the geometric one: a smooth mesh's blend of vertex
    // normals. nullptr (the usual case): the normal, which then does both jobs.
    ShadingNormalFn* shading_normal = nullptr;
    // For a flat primitive that a fan of triangles from its first corner covers (polygon,
    // triangle): its corners, for handing it to another library as triangles (bench/embree).
    // nullptr: not such a primitive.
    CornersFn* corners = nullptr;
    // True where one test searches many parts: a mesh's triangles (14, 15, 16), a
    // composite's operands (CSG); an affine frame asks its inner primitive. The object
    // hierarchy then asks a shadow ray's last blocker only behind its box, where a cheap
    // primitive is asked first. nullptr: false.
    PropertyFn* many_parts = nullptr;
    // Where the primitive's test starts with a hierarchy of its own over its parts, whose
    // boxes hold all of them (a mesh's triangles: 14, 15, 16): boxes of a cut across it. A
    // ray outside its box then costs it about one box test, so a scene whose one bounded
    // object this is asks it directly rather than testing its box first, and the boxes
    // tell which pixels' rays may meet it (render/primary_mask.h). nullptr: no hierarchy.
    OutlineFn* outline = nullptr;
    // For a primitive with such a hierarchy: intersect and intersect_any that walk it with
    // the ray the object hierarchy's walk prepared, rather than prepare it again (three
    // divisions and some sixty instructions, a tenth of the SPD's teapot). The same answers
    // as intersect and intersect_any. nullptr: the object hierarchy calls those.
    PreparedIntersectFn* intersect_prepared = nullptr;
    PreparedIntersectFn* intersect_any_prepared = nullptr;
    // For a primitive that is a sphere and nothing else (1): its centre and squared radius,
    // which the object hierarchy copies into its leaves to test it inline, without a call
    // (primitives/sphere_test.h, the same code as its intersect). nullptr: not a sphere.
    SphereFn* sphere = nullptr;
};

// One row of the table: the scene format's ID, the name messages use, and what it does.
struct PrimitiveType {
    int id;
    const char* name;
    const PrimitiveFunctions* functions;
};

// A primitive type with its parameters: what the scene stores for each primitive.
struct Shape {
    const PrimitiveType* type = nullptr;
    // The type's functions, held here as well so that a call through a shape (an affine's
    // inner primitive, a composite's operands) costs one load, as through the hierarchy.
    const PrimitiveFunctions* functions = nullptr;
    ShapeData data;

    Shape() = default;
    Shape(const PrimitiveType* row, ShapeData parameters)
        : type(row), functions(row->functions), data(std::move(parameters)) {}

    bool intersect(const Ray& ray, Interval range, Hit& hit) const {
        return functions->intersect(data.get(), ray, range, hit);
    }
    IntersectFn* intersect_function() const { return functions->intersect; }
    IntersectFn* any_hit_function() const {
        return functions->intersect_any != nullptr ? functions->intersect_any
                                                   : functions->intersect;
    }
    // Whether anything of the primitive lies along the ray in range.
    bool intersect_any(const Ray& ray, Interval range) const {
        Hit scratch;
        return any_hit_function()(data.get(), ray, range, scratch);
    }
    Vec3 normal(const Vec3& point, const Hit& hit) const {
        return functions->normal(data.get(), point, hit);
    }
    bool has_shading_normal() const { return functions->shading_normal != nullptr; }
    // The shading normal, or the normal where the type has none of its own; `normal` is
    // normal(point, hit), already computed.
    Vec3 shading_normal(const Vec3& point, const Hit& hit, const Vec3& normal) const {
        return has_shading_normal() ? functions->shading_normal(data.get(), point, hit, normal)
                                    : normal;
    }
    Vec3 shading_normal(const Vec3& point, const Hit& hit) const {
        return shading_normal(point, hit, normal(point, hit));
    }
    Bounds bounds() const { return functions->bounds(data.get()); }
    bool has_inside() const {
        return functions->inside != nullptr &&
               (functions->has_inside == nullptr || functions->has_inside(data.get()));
    }
    // Only meaningful when has_inside().
    bool inside(const Vec3& point) const { return functions->inside(data.get(), point); }
    // The nearest crossing of the solid's boundary in range (only when has_inside()).
    bool cross(const Ray& ray, Interval range, Crossing& crossing) const;
    // Every crossing beyond t_min, and whether the ray starts inside (only when has_inside()).
    bool collect(const Ray& ray, double t_min, Crossings& out) const;
    Bounds solid_bounds() const {
        return functions->solid_bounds != nullptr ? functions->solid_bounds(data.get()) : bounds();
    }
    bool carries_surfaces() const {
        return functions->carries_surfaces != nullptr && functions->carries_surfaces(data.get());
    }
    bool many_parts() const {
        return functions->many_parts != nullptr && functions->many_parts(data.get());
    }
    bool own_hierarchy() const { return functions->outline != nullptr; }
};

// Crossings of one boundary are searched for again from just past the last one: by this much
// relative to its distance, so that rounding in a frame's transform cannot find it twice.
inline constexpr double kCrossingStep = 1e-12;
// The smallest distance past t where the next crossing is looked for.
double step_past(double t);

// The whole table, sorted by ID.
std::span<const PrimitiveType> primitive_types();
// The row for an ID, or nullptr when no primitive has that ID.
const PrimitiveType* find_primitive_type(int id);

}  // namespace rt
