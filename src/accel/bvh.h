// A bounding volume hierarchy over boxes, written once and used twice: over the scene's
// objects (object_index.h) and over the triangles inside a mesh. It knows nothing of what
// the boxes hold: traversal calls back with each candidate's place in leaf order.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "rt/ray.h"

namespace rt {

// One node of the flattened tree: 32 bytes, two to a cache line. Boxes are floats rounded
// outward, so a node's box always holds everything below it.
struct BvhNode {
    float bound[6];  // the min corner's x, y, z, then the max corner's
    // In a leaf, the first of its primitives in leaf order; in an interior node, the index of
    // the second child (the first child is always the next node).
    std::uint32_t offset;
    std::uint16_t count;  // primitives in a leaf; 0 for an interior node
    std::uint16_t unused;

    bool is_leaf() const { return count != 0; }
};
static_assert(sizeof(BvhNode) == 32);

// A ray prepared for many box tests: the reciprocal of its direction, and for each axis which
// of a node's two bounds the ray meets first.
class BoxRay {
  public:
    explicit BoxRay(const Ray& ray);

    // Whether the ray passes through the node's box somewhere in [t_min, t_max]; if so,
    // t_enter is where (from t_min on) it enters. The range starts as [t_min, t_max], each
    // slab narrows it, and the result is widened by a relative margin so that a hit a
    // primitive computes at the box's very edge, or at exactly t_max (a tie), is never
    // pruned. A ray parallel to a slab whose origin lies on the slab's plane makes 0 * inf =
    // NaN there; the comparisons below then ignore that slab, which only keeps more.
    bool enters(const BvhNode& node, double t_min, double t_max, double& t_enter) const {
        double near = t_min, far = t_max;
        for (int k = 0; k < 3; ++k) {
            const double slab_near = (node.bound[near_bound_[k]] - origin_[k]) * inverse_[k];
            const double slab_far = (node.bound[far_bound_[k]] - origin_[k]) * inverse_[k];
            if (slab_near > near) near = slab_near;
            if (slab_far < far) far = slab_far;
        }
        near -= kMargin * std::fabs(near);
        far += kMargin * std::fabs(far);
        t_enter = near;
        return near <= far;
    }

  private:
    static constexpr double kMargin = 1e-9;
    double origin_[3];
    double inverse_[3];
    // Per axis, which of a node's bounds the ray meets first and last: k for the min, 3 + k
    // for the max.
    int near_bound_[3];
    int far_bound_[3];
};

class Bvh {
  public:
    // The most primitives a leaf holds; a leaf's count must fit its 16 bits.
    static constexpr std::size_t kMaxLeafSize = 8;
    // Deeper than this, nodes split at the median of their primitives, so traversal's
    // fixed stack can never overflow (see kStackSize).
    static constexpr int kMaxSahDepth = 48;

    Bvh() = default;
    // Builds over the given boxes, which must be finite, with binned SAH splits, on up to
    // `threads` threads (the result is the same for any number). Primitive i is the one with
    // boxes[i]; order() lists them as the leaves hold them.
    explicit Bvh(std::span<const Bounds> boxes, int threads = 1);

    std::span<const BvhNode> nodes() const { return nodes_; }
    std::span<const std::uint32_t> order() const { return order_; }
    // Gives up the leaf order, for an owner that stores its primitives in that order itself.
    std::vector<std::uint32_t> take_order() { return std::move(order_); }

    // Calls visit(position) for each primitive (its place in leaf order) whose leaf the ray
    // may reach in [t_min, t_max], nearer leaves first. visit may lower t_max, the best hit
    // so far, which prunes the rest; a leaf entered exactly at t_max is still visited, so
    // the caller can break ties.
    template <class Visit>
    void closest(const Ray& ray, double t_min, double& t_max, Visit&& visit) const;
    // Calls visit(position) for candidates in [t_min, t_max] until one returns true; returns
    // whether one did.
    template <class Visit>
    bool any(const Ray& ray, double t_min, double t_max, Visit&& visit) const;

  private:
    // With at most kMaxSahDepth SAH levels and median splits below them, no path is longer
    // than kMaxSahDepth + 32 nodes for fewer than 2^32 primitives; the stack holds one
    // entry per level.
    static constexpr int kStackSize = kMaxSahDepth + 40;

    template <class Leaf>
    void walk(const Ray& ray, double t_min, const double& t_max, Leaf&& leaf) const;

    std::vector<BvhNode> nodes_;
    std::vector<std::uint32_t> order_;
};

// Nodes are visited depth first. At an interior node both children's boxes are tested; the
// ray goes on into the one it enters first, and the other waits on a small fixed stack with
// its entry distance, so that it is dropped without another test once a hit nearer than
// that has been found. leaf(node) returns true to stop.
template <class Leaf>
void Bvh::walk(const Ray& ray, double t_min, const double& t_max, Leaf&& leaf) const {
    if (nodes_.empty()) return;
    const BoxRay box_ray(ray);
    struct Pending {
        std::uint32_t node;
        double t_enter;
    };
    Pending stack[kStackSize];
    int top = 0;
    std::uint32_t current = 0;
    double t_enter = 0;
    if (!box_ray.enters(nodes_[0], t_min, t_max, t_enter)) return;
    for (;;) {
        const BvhNode& node = nodes_[current];
        if (!node.is_leaf()) {
            std::uint32_t first = current + 1, second = node.offset;
            double t_first = 0, t_second = 0;
            const bool enters_first = box_ray.enters(nodes_[first], t_min, t_max, t_first);
            const bool enters_second = box_ray.enters(nodes_[second], t_min, t_max, t_second);
            if (enters_first && enters_second) {
                if (t_second < t_first) {
                    std::swap(first, second);
                    std::swap(t_first, t_second);
                }
                stack[top++] = {second, t_second};
                current = first;
                continue;
            }
            if (enters_first || enters_second) {
                current = enters_first ? first : second;
                continue;
            }
        } else if (leaf(node)) {
            return;
        }
        // Pop until a node the ray enters before the best hit so far (t_max may have fallen
        // since it was pushed).
        for (;;) {
            if (top == 0) return;
            const Pending& next = stack[--top];
            if (next.t_enter <= t_max) {
                current = next.node;
                break;
            }
        }
    }
}

template <class Visit>
void Bvh::closest(const Ray& ray, double t_min, double& t_max, Visit&& visit) const {
    walk(ray, t_min, t_max, [&](const BvhNode& node) {
        for (std::uint32_t i = node.offset, end = node.offset + node.count; i < end; ++i) visit(i);
        return false;
    });
}

template <class Visit>
bool Bvh::any(const Ray& ray, double t_min, double t_max, Visit&& visit) const {
    bool found = false;
    walk(ray, t_min, t_max, [&](const BvhNode& node) {
        for (std::uint32_t i = node.offset, end = node.offset + node.count; i < end; ++i)
            if (visit(i)) return found = true;
        return false;
    });
    return found;
}

}  // namespace rt
