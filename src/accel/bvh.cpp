// Building the hierarchy: top down, each node split where the surface area heuristic (SAH),
// evaluated at a few bin boundaries along the centroids' longest axis, says a ray will do
// the least work; nodes are written straight into the flat array in depth-first order.
#include "rt/bvh.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>

namespace rt {

namespace {

// Bin boundaries per split. More bins find slightly better splits and cost build time.
constexpr int kBins = 16;
// The cost of visiting a node, relative to testing one primitive.
constexpr double kTraversalCost = 1.0;
// Boxes are widened by this much relative to their coordinates, so that a hit point a
// primitive computes a rounding error outside its exact bounds still lies in its node.
constexpr double kBoxPadding = 1e-9;

double half_area(const Bounds& b) {
    const Vec3 d = b.max - b.min;
    return d.x * d.y + d.y * d.z + d.z * d.x;
}

Bounds merged(const Bounds& a, const Bounds& b) {
    return {component_min(a.min, b.min), component_max(a.max, b.max)};
}

// The nearest float below (above) a double: a float box rounded this way holds the double one.
float float_below(double v) {
    if (v > FLT_MAX) return FLT_MAX;
    if (!(v >= -FLT_MAX)) return -HUGE_VALF;
    const float f = static_cast<float>(v);
    return static_cast<double>(f) > v ? std::nextafter(f, -HUGE_VALF) : f;
}
float float_above(double v) {
    if (v < -FLT_MAX) return -FLT_MAX;
    if (!(v <= FLT_MAX)) return HUGE_VALF;
    const float f = static_cast<float>(v);
    return static_cast<double>(f) < v ? std::nextafter(f, HUGE_VALF) : f;
}

class Builder {
  public:
    Builder(std::span<const Bounds> boxes, std::vector<BvhNode>& nodes,
            std::vector<std::uint32_t>& order)
        : boxes_(boxes), nodes_(nodes), order_(order) {
        centroids_.reserve(boxes.size());
        // Halves first: min + max can overflow where neither does.
        for (const Bounds& b : boxes) centroids_.push_back(b.min * 0.5 + b.max * 0.5);
    }

    void build(std::uint32_t begin, std::uint32_t end, int depth);

  private:
    struct Split {
        std::uint32_t mid = 0;  // order_[begin, mid) goes to the first child
        int axis = 0;
        bool leaf = false;
    };
    Split choose_split(std::uint32_t begin, std::uint32_t end, int depth, const Bounds& box);
    std::uint32_t median_split(std::uint32_t begin, std::uint32_t end, int axis);
    void write_box(BvhNode& node, const Bounds& box) const;

    std::span<const Bounds> boxes_;
    std::vector<Vec3> centroids_;
    std::vector<BvhNode>& nodes_;
    std::vector<std::uint32_t>& order_;
};

void Builder::write_box(BvhNode& node, const Bounds& box) const {
    const double pad =
        kBoxPadding * (1 + std::fmax(max_abs_component(box.min), max_abs_component(box.max)));
    for (int k = 0; k < 3; ++k) {
        node.min[k] = float_below(box.min[k] - pad);
        node.max[k] = float_above(box.max[k] + pad);
    }
}

void Builder::build(std::uint32_t begin, std::uint32_t end, int depth) {
    Bounds box;
    for (std::uint32_t i = begin; i < end; ++i) box = merged(box, boxes_[order_[i]]);
    const std::size_t index = nodes_.size();
    nodes_.push_back({});
    write_box(nodes_[index], box);

    const Split split = choose_split(begin, end, depth, box);
    if (split.leaf) {
        nodes_[index].offset = begin;
        nodes_[index].count = static_cast<std::uint16_t>(end - begin);
        return;
    }
    nodes_[index].axis = static_cast<std::uint8_t>(split.axis);
    build(begin, split.mid, depth + 1);
    nodes_[index].offset = static_cast<std::uint32_t>(nodes_.size());
    build(split.mid, end, depth + 1);
}

std::uint32_t Builder::median_split(std::uint32_t begin, std::uint32_t end, int axis) {
    const std::uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](std::uint32_t a, std::uint32_t b) {
                         return centroids_[a][axis] < centroids_[b][axis];
                     });
    return mid;
}

Builder::Split Builder::choose_split(std::uint32_t begin, std::uint32_t end, int depth,
                                     const Bounds& box) {
    const std::uint32_t count = end - begin;
    if (count == 1) return {.leaf = true};

    Bounds centroid_box;
    for (std::uint32_t i = begin; i < end; ++i) centroid_box.expand(centroids_[order_[i]]);
    const Vec3 extent = centroid_box.max - centroid_box.min;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                     : extent.y >= extent.z                       ? 1
                                                                  : 2;
    const bool fits_leaf = count <= Bvh::kMaxLeafSize;
    // All centroids in one place: no split separates them, so a leaf or an even split.
    if (!(extent[axis] > 0)) {
        if (fits_leaf) return {.leaf = true};
        return {.mid = begin + count / 2, .axis = axis};
    }
    if (depth >= Bvh::kMaxSahDepth) return {.mid = median_split(begin, end, axis), .axis = axis};

    // Count the primitives and grow a box per bin of centroids along the axis.
    const double origin = centroid_box.min[axis];
    const double scale = kBins / extent[axis];
    auto bin_of = [&](std::uint32_t primitive) {
        const double b = (centroids_[primitive][axis] - origin) * scale;
        return b >= kBins - 1 ? kBins - 1 : static_cast<int>(b);  // also takes inf
    };
    std::array<std::uint32_t, kBins> bin_count{};
    std::array<Bounds, kBins> bin_box{};
    for (std::uint32_t i = begin; i < end; ++i) {
        const std::uint32_t p = order_[i];
        const auto b = static_cast<std::size_t>(bin_of(p));
        ++bin_count[b];
        bin_box[b] = merged(bin_box[b], boxes_[p]);
    }
    // Sweep from the right for the boxes above each boundary, then from the left: the cost
    // of splitting after bin s is that of visiting both children, weighted by the chance
    // (their area over the parent's) that a ray through the parent enters each.
    std::array<double, kBins> area_above{};
    Bounds above;
    for (int s = kBins - 1; s > 0; --s) {
        above = merged(above, bin_box[static_cast<std::size_t>(s)]);
        area_above[static_cast<std::size_t>(s)] = half_area(above);
    }
    double best_cost = kInfinity;
    int best_bin = -1;
    Bounds below;
    std::uint32_t count_below = 0;
    for (int s = 0; s < kBins - 1; ++s) {
        const auto i = static_cast<std::size_t>(s);
        below = merged(below, bin_box[i]);
        count_below += bin_count[i];
        const std::uint32_t count_above = count - count_below;
        if (count_below == 0 || count_above == 0) continue;
        const double cost = count_below * half_area(below) + count_above * area_above[i + 1];
        if (cost < best_cost) {
            best_cost = cost;
            best_bin = s;
        }
    }
    const double parent_area = half_area(box);
    best_cost = kTraversalCost + best_cost / parent_area;
    if (fits_leaf && !(best_cost < count)) return {.leaf = true};
    // Rounding put every centroid in one bin, or the areas overflowed: split evenly.
    if (best_bin < 0 || !std::isfinite(best_cost))
        return {.mid = median_split(begin, end, axis), .axis = axis};

    const auto mid = std::partition(order_.begin() + begin, order_.begin() + end,
                                    [&](std::uint32_t p) { return bin_of(p) <= best_bin; });
    return {.mid = static_cast<std::uint32_t>(mid - order_.begin()), .axis = axis};
}

}  // namespace

BoxRay::BoxRay(const Ray& ray) {
    for (int k = 0; k < 3; ++k) {
        origin_[k] = ray.origin[k];
        inverse_[k] = 1 / ray.direction[k];  // +-inf for a zero component: see enters()
        negative_[k] = std::signbit(inverse_[k]);
    }
}

Bvh::Bvh(std::span<const Bounds> boxes) {
    if (boxes.empty()) return;
    order_.resize(boxes.size());
    for (std::uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
    // A binary tree with n leaves has 2n - 1 nodes; reserving them keeps the build from
    // reallocating (pages never touched cost no memory), and the fit afterwards trims it.
    nodes_.reserve(2 * boxes.size() - 1);
    Builder(boxes, nodes_, order_).build(0, static_cast<std::uint32_t>(boxes.size()), 0);
    nodes_.shrink_to_fit();
}

Bounds Bvh::bounds() const {
    if (nodes_.empty()) return {};
    const BvhNode& root = nodes_[0];
    return {{root.min[0], root.min[1], root.min[2]}, {root.max[0], root.max[1], root.max[2]}};
}

}  // namespace rt
