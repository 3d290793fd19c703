#include "rt/object_index.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "rt/scene.h"

namespace rt {

namespace {

bool finite_box(const Bounds& b) {
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(b.min[k]) || !std::isfinite(b.max[k]) || !(b.min[k] <= b.max[k]))
            return false;
    return true;
}

}  // namespace

ObjectIndex::ObjectIndex(std::span<const Object> objects) : object_count_(objects.size()) {
    if (objects.size() > std::numeric_limits<std::uint32_t>::max())
        throw std::length_error("too many objects for the hierarchy");
    std::vector<Bounds> boxes;
    std::vector<Entry> bounded;
    for (std::uint32_t i = 0; i < objects.size(); ++i) {
        const Shape& shape = objects[i].shape;
        const Entry entry{shape.type->intersect, shape.data.get(), i};
        const Bounds box = shape.bounds();
        if (finite_box(box)) {
            boxes.push_back(box);
            bounded.push_back(entry);
        } else {
            unbounded_.push_back(entry);
        }
    }
    bvh_ = Bvh(boxes);
    bounded_.reserve(bounded.size());
    for (const std::uint32_t i : bvh_.take_order()) bounded_.push_back(bounded[i]);
}

bool ObjectIndex::closest(const Ray& ray, Interval range, Found& found) const {
    constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
    double best = range.t_max;
    std::uint32_t best_object = kNone;
    // An object earlier in the file than the best so far also wins at the same distance,
    // so it is asked for hits up to just past the best.
    auto test = [&](const Entry& e) {
        const bool earlier = best_object != kNone && e.object < best_object;
        const double limit = earlier ? std::nextafter(best, kInfinity) : best;
        Hit hit;
        if (!e.intersect(e.data, ray, {range.t_min, limit}, hit)) return;
        best = hit.t;
        best_object = e.object;
        found = {e.object, hit};
    };
    // The unbounded objects first: a floor under everything prunes much of the tree.
    for (const Entry& e : unbounded_) test(e);
    bvh_.closest(ray, range.t_min, best, [&](std::uint32_t i) { test(bounded_[i]); });
    return best_object != kNone;
}

bool ObjectIndex::any(const Ray& ray, Interval range) const {
    Hit hit;
    auto blocks = [&](const Entry& e) { return e.intersect(e.data, ray, range, hit); };
    for (const Entry& e : unbounded_)
        if (blocks(e)) return true;
    return bvh_.any(ray, range.t_min, range.t_max,
                    [&](std::uint32_t i) { return blocks(bounded_[i]); });
}

}  // namespace rt
