// The hierarchy over a scene's objects: what the tracer asks for the nearest hit along a ray
// and for any blocker of a shadow ray, instead of testing every object in turn.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "rt/bvh.h"
#include "rt/primitive.h"

namespace rt {

struct Object;

class ObjectIndex {
  public:
    // The nearest hit and the object's place in the scene's list.
    struct Found {
        std::uint32_t object;
        Hit hit;
    };

    ObjectIndex() = default;
    // Objects with finite bounds go into the hierarchy; the rest (planes, and affines of
    // them) stay in a short list tested on every ray.
    explicit ObjectIndex(std::span<const Object> objects);

    // Whether this index was built over exactly `count` objects.
    bool covers(std::size_t count) const { return object_count_ == count; }
    std::size_t bounded_count() const { return bounded_.size(); }
    std::size_t unbounded_count() const { return unbounded_.size(); }

    // The nearest hit in range, exactly as testing every object in file order finds it: the
    // smallest distance, and of objects hit at the same distance, the one earliest in the
    // file.
    bool closest(const Ray& ray, Interval range, Found& found) const;
    // Whether any object is hit in range.
    bool any(const Ray& ray, Interval range) const;

  private:
    // What a test needs, stored contiguously in the order the leaves visit them.
    struct Entry {
        IntersectFn* intersect;
        const void* data;
        std::uint32_t object;
    };

    Bvh bvh_;
    std::vector<Entry> bounded_;    // in leaf order
    std::vector<Entry> unbounded_;  // in file order
    std::size_t object_count_ = 0;
};

}  // namespace rt
