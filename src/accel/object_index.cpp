#include "rt/object_index.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "rt/scene.h"

namespace rt {

namespace {

// How far past the best hit so far an object is asked for hits (relative).
constexpr double kTieSlack = 1e-9;

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
    auto test = [&](const Entry& e) {
        // The linear scan asks each object with its own best so far, and an intersect's
        // answer near t_max can depend on t_max by a rounding (an affine scales it), so each
        // object is asked a little past the best, and the answer is judged here: nearer wins,
        // and at the same distance the object earlier in the file.
        const double limit = best_object == kNone ? best : best + kTieSlack * best;
        Hit hit;
        if (!e.intersect(e.data, ray, {range.t_min, limit}, hit)) return;
        if (!(hit.t < best || (hit.t == best && e.object < best_object))) return;
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
