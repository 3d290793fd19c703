// Union (20), intersection (21) and difference (22): operand A (ID, numbers, surface), then
// operand B (the same). The composite is the boundary of the set A ∪ B, A ∩ B or A − B; each
// point of it keeps the surface of the operand it lies on, and its normal points out of the
// composite (B's is turned around in a difference).
//
// Along a ray each operand's boundary crossings are listed in order with the side they lead
// to; merging the two lists and keeping the crossings where membership of the set changes
// gives the composite's own list (Roth's ray casting of CSG). Nested composites are lists of
// lists, so the cost grows with the number of operands, not with the depth of nesting.
#include <algorithm>
#include <string>

#include "rt/primitive.h"
#include "rt/reader.h"

namespace rt::csg {

namespace {

enum class Operation { unite, intersect, subtract };

struct Operand {
    Shape shape;
    SurfacePtr surface;  // nullptr when the operand carries its own (a nested composite)
};

struct Csg {
    Operation operation;
    Operand a;
    Operand b;
    Bounds surface_box;
    Bounds solid_box;
};

bool in_set(Operation operation, bool in_a, bool in_b) {
    switch (operation) {
        case Operation::unite:
            return in_a || in_b;
        case Operation::intersect:
            return in_a && in_b;
        case Operation::subtract:
            return in_a && !in_b;
    }
    return false;
}

const char* name_of(Operation operation) {
    switch (operation) {
        case Operation::unite:
            return "union";
        case Operation::intersect:
            return "intersection";
        case Operation::subtract:
            return "difference";
    }
    return "";
}

std::string with_article(const std::string& name) {
    return (name.find_first_of("aeiou") == 0 ? "an " : "a ") + name;
}

Operand read_operand(SceneReader& reader, Operation operation, const char* which) {
    const std::string what = std::string(name_of(operation)) + " operand " + which;
    const Location where = reader.next_location();
    Shape shape = reader.shape(what);
    if (!shape.has_inside())
        reader.fail(where, what + " is " + with_article(shape.type->name) + " (" +
                               std::to_string(shape.type->id) +
                               "), which has no inside; operands must be solids: sphere, plane, "
                               "torus, box, quadric, an affine of one, or a union, "
                               "intersection or difference");
    // A nested composite carries its operands' surfaces; anything else is followed by one.
    SurfacePtr surface = shape.carries_surfaces() ? nullptr : reader.surface();
    return {std::move(shape), std::move(surface)};
}

// A box for nothing at all (two solids apart): a point, so that the hierarchy can hold it.
Bounds non_empty(const Bounds& box, const Vec3& fallback) {
    return box.empty() ? Bounds{fallback, fallback} : box;
}

ShapeData read(SceneReader& reader, Operation operation) {
    Operand a = read_operand(reader, operation, "A");
    Operand b = read_operand(reader, operation, "B");
    const Bounds a_surface = a.shape.bounds(), b_surface = b.shape.bounds();
    const Bounds a_solid = a.shape.solid_bounds(), b_solid = b.shape.solid_bounds();
    // Every visible point lies on an operand's surface and, where the other operand decides
    // whether it shows, inside or outside that operand's solid.
    Bounds surface_box, solid_box;
    switch (operation) {
        case Operation::unite:
            surface_box = merged(a_surface, b_surface);
            solid_box = merged(a_solid, b_solid);
            break;
        case Operation::intersect:
            surface_box = merged(overlap(a_surface, b_solid), overlap(b_surface, a_solid));
            solid_box = overlap(a_solid, b_solid);
            break;
        case Operation::subtract:
            surface_box = merged(a_surface, overlap(b_surface, a_solid));
            solid_box = a_solid;
            break;
    }
    // overlap() of a box with an empty one is empty, and merged() keeps the other side.
    surface_box = non_empty(surface_box, a_surface.min);
    solid_box = non_empty(solid_box, surface_box.min);
    return std::make_shared<const Csg>(
        Csg{operation, std::move(a), std::move(b), surface_box, solid_box});
}

// One operand's crossing as the composite reports it: which operand (a bit on the path) and,
// unless a nested composite already named one, whose surface.
Crossing tagged(Crossing crossing, const Operand& operand, unsigned which) {
    crossing.hit.path = (crossing.hit.path << 1) | which;
    if (crossing.hit.surface == nullptr) crossing.hit.surface = operand.surface.get();
    return crossing;
}

ShapeData read_union(SceneReader& reader) { return read(reader, Operation::unite); }
ShapeData read_intersection(SceneReader& reader) { return read(reader, Operation::intersect); }
ShapeData read_difference(SceneReader& reader) { return read(reader, Operation::subtract); }

bool collect(const void* shape, const Ray& ray, double t_min, Crossings& out) {
    const auto& c = *static_cast<const Csg*>(shape);
    const std::size_t a_begin = out.size();
    bool in_a = c.a.shape.collect(ray, t_min, out);
    const std::size_t b_begin = out.size();
    bool in_b = c.b.shape.collect(ray, t_min, out);
    const std::size_t b_end = out.size();
    const bool started_inside = in_set(c.operation, in_a, in_b);

    // Merge the two lists, appending the composite's crossings after them. Crossings at the
    // same distance are taken together, so coincident faces that cancel leave nothing. Each
    // pass consumes at least one crossing because no distance is NaN (Shape::collect stops
    // at a crossing it cannot place).
    bool inside_now = started_inside;
    std::size_t i = a_begin, j = b_begin;
    while (i < b_begin || j < b_end) {
        const double t =
            std::min(i < b_begin ? out[i].hit.t : kInfinity, j < b_end ? out[j].hit.t : kInfinity);
        Crossing decisive;
        bool from_a = false;
        for (; i < b_begin && out[i].hit.t == t; ++i) {
            in_a = out[i].entering;
            decisive = tagged(out[i], c.a, 0);
            from_a = true;
        }
        for (; j < b_end && out[j].hit.t == t; ++j) {
            in_b = out[j].entering;
            if (!from_a) decisive = tagged(out[j], c.b, 1);
        }
        const bool inside_next = in_set(c.operation, in_a, in_b);
        if (inside_next == inside_now) continue;
        inside_now = inside_next;
        decisive.entering = inside_next;
        out.push_back(decisive);
    }
    // Replace the operands' lists with the composite's.
    const auto merged_begin = out.begin() + static_cast<std::ptrdiff_t>(b_end);
    std::move(merged_begin, out.end(), out.begin() + static_cast<std::ptrdiff_t>(a_begin));
    out.resize(a_begin + (out.size() - b_end));
    return started_inside;
}

bool intersect(const void* shape, const Ray& ray, Interval range, Hit& hit) {
    // Per thread, and used above whatever an enclosing call has in it.
    thread_local Crossings scratch;
    const std::size_t base = scratch.size();
    collect(shape, ray, range.t_min, scratch);
    bool found = false;
    for (std::size_t i = base; i < scratch.size() && scratch[i].hit.t < range.t_max; ++i) {
        if (scratch[i].visible) {
            hit = scratch[i].hit;
            found = true;
            break;
        }
    }
    scratch.resize(base);
    return found;
}

Vec3 normal(const void* shape, const Vec3& point, const Hit& hit) {
    const auto& c = *static_cast<const Csg*>(shape);
    const bool from_b = (hit.path & 1) != 0;
    Hit operand_hit = hit;
    operand_hit.path >>= 1;
    const Vec3 n = (from_b ? c.b : c.a).shape.normal(point, operand_hit);
    return from_b && c.operation == Operation::subtract ? -n : n;
}

Bounds bounds(const void* shape) { return static_cast<const Csg*>(shape)->surface_box; }

Bounds solid_bounds(const void* shape) { return static_cast<const Csg*>(shape)->solid_box; }

bool inside(const void* shape, const Vec3& point) {
    const auto& c = *static_cast<const Csg*>(shape);
    return in_set(c.operation, c.a.shape.inside(point), c.b.shape.inside(point));
}

bool carries_surfaces(const void*) { return true; }
bool many_parts(const void*) { return true; }

// Composites: their operands bring their own surfaces, and the boundary is found from
// the operands' crossings. The three differ only in how they read.
constexpr PrimitiveFunctions composite(ReadShapeFn* read_operation) {
    return {.read = read_operation,
            .intersect = intersect,
            .normal = normal,
            .bounds = bounds,
            .inside = inside,
            .carries_surfaces = carries_surfaces,
            .collect = collect,
            .solid_bounds = solid_bounds,
            .many_parts = many_parts};
}

}  // namespace

extern const PrimitiveFunctions union_functions = composite(read_union);
extern const PrimitiveFunctions intersection_functions = composite(read_intersection);
extern const PrimitiveFunctions difference_functions = composite(read_difference);

}  // namespace rt::csg
