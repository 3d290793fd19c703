// Building the hierarchy: top down, each node split where the surface area heuristic (SAH),
// evaluated at a few bin boundaries along the centroids' longest axis, says a ray will do
// the least work; nodes are written straight into the flat array in depth-first order.
//
// The build works on a compact copy of the boxes (floats, rounded outward, with the
// primitive's index), partitioned in place, so every pass reads memory in order. One pass per
// node bins the primitives; the bins already hold the children's boxes, so the partition that
// follows is the only other pass.
#include "accel/bvh.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <exception>
#include <thread>

namespace rt {

namespace {

// Bin boundaries per split. More bins find slightly better splits and cost build time.
constexpr int kBins = 16;
// The cost of visiting a node, relative to testing one primitive.
constexpr double kTraversalCost = 2.0;
// Boxes are widened by this much relative to their coordinates, so that a hit point a
// primitive computes a rounding error outside its exact bounds still lies in its node.
constexpr double kBoxPadding = 1e-9;
// Below this many primitives a subtree is not worth a thread of its own.
constexpr std::uint32_t kParallelBuildMinimum = 50000;

// A float at or below (above) a double, so that a float box holds the double one. Moving
// the value out by a float's relative precision first leaves room for the conversion's
// rounding to the nearest float; near zero, where that room is smallest, the caller's
// padding (at least kBoxPadding) covers it.
float float_below(double v) {
    const double x = v - std::fabs(v) * 0x1p-23;
    if (x > FLT_MAX) return FLT_MAX;
    return x < -FLT_MAX ? -HUGE_VALF : static_cast<float>(x);
}
float float_above(double v) {
    const double x = v + std::fabs(v) * 0x1p-23;
    if (x < -FLT_MAX) return -FLT_MAX;
    return x > FLT_MAX ? HUGE_VALF : static_cast<float>(x);
}

// A box of floats; empty (lo > hi) until something is added.
struct Box {
    float lo[3] = {HUGE_VALF, HUGE_VALF, HUGE_VALF};
    float hi[3] = {-HUGE_VALF, -HUGE_VALF, -HUGE_VALF};

    void add(const Box& b) {
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], b.lo[k]);
            hi[k] = std::max(hi[k], b.hi[k]);
        }
    }
    void add_point(const float p[3]) {
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], p[k]);
            hi[k] = std::max(hi[k], p[k]);
        }
    }
    // In double: a float box's sides can overflow a float product.
    double half_area() const {
        if (!(lo[0] <= hi[0])) return 0;
        double d[3];
        for (int k = 0; k < 3; ++k) d[k] = static_cast<double>(hi[k]) - lo[k];
        return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
    }
};

// One primitive as the build sees it: its box, the box's centre and the primitive's index.
struct Reference {
    Box box;
    float centre[3];
    std::uint32_t index;
};

Reference make_reference(const Bounds& b, std::uint32_t index) {
    const double pad =
        kBoxPadding * (1 + std::fmax(max_abs_component(b.min), max_abs_component(b.max)));
    Reference r{{}, {}, index};
    for (int k = 0; k < 3; ++k) {
        r.box.lo[k] = float_below(b.min[k] - pad);
        r.box.hi[k] = float_above(b.max[k] + pad);
        // Halves first: min + max can overflow where neither does.
        r.centre[k] = static_cast<float>(std::clamp(b.min[k] * 0.5 + b.max[k] * 0.5,
                                                    static_cast<double>(-FLT_MAX),
                                                    static_cast<double>(FLT_MAX)));
    }
    return r;
}

// A range of references with the box of their boxes and the box of their centres.
struct Range {
    std::uint32_t begin, end;
    Box box, centres;

    std::uint32_t count() const { return end - begin; }
};

class Builder {
  public:
    Builder(std::vector<Reference>& refs, std::vector<BvhNode>& nodes)
        : refs_(refs), nodes_(nodes) {}

    Range whole() const { return measured(0, static_cast<std::uint32_t>(refs_.size())); }
    // Writes the subtree over the range into nodes_, depth first, using up to `threads`
    // threads: a second thread builds a large node's second child into nodes of its own,
    // appended afterwards, so the array is the same however many threads built it.
    void build(const Range& range, int depth, int threads);

  private:
    struct Bin {
        std::uint32_t count = 0;
        Box box;
    };
    struct SahSplit {
        double cost = kInfinity;  // relative to testing one primitive
        bool found = false;       // false when no boundary separates the primitives
        std::pair<Range, Range> children;
    };

    // The best of the splits between bins of centres along the axis, already partitioned.
    SahSplit sah_split(const Range& range, int axis, double extent);

    // Moves the references for which goes_first holds to the front of the range; returns
    // the two parts with their centroid boxes (their boxes are left to the caller).
    template <class Predicate>
    std::pair<Range, Range> partition(const Range& range, Predicate goes_first);

    Range measured(std::uint32_t begin, std::uint32_t end) const;
    // Splits in the middle of the range, for primitives no position separates.
    std::pair<Range, Range> median_split(const Range& range, int axis);
    void make_leaf(std::size_t node, const Range& range);
    void build_children(std::size_t node, const std::pair<Range, Range>& children, int depth,
                        int threads);

    std::vector<Reference>& refs_;
    std::vector<BvhNode>& nodes_;
};

Range Builder::measured(std::uint32_t begin, std::uint32_t end) const {
    Range r{begin, end, {}, {}};
    for (std::uint32_t i = begin; i < end; ++i) {
        r.box.add(refs_[i].box);
        r.centres.add_point(refs_[i].centre);
    }
    return r;
}

std::pair<Range, Range> Builder::median_split(const Range& range, int axis) {
    const std::uint32_t mid = range.begin + range.count() / 2;
    std::nth_element(
        refs_.begin() + range.begin, refs_.begin() + mid, refs_.begin() + range.end,
        [axis](const Reference& a, const Reference& b) { return a.centre[axis] < b.centre[axis]; });
    return {measured(range.begin, mid), measured(mid, range.end)};
}

template <class Predicate>
std::pair<Range, Range> Builder::partition(const Range& range, Predicate goes_first) {
    Range first{range.begin, range.begin, {}, {}};
    Range second{range.end, range.end, {}, {}};
    // Hoare's scheme: grow the first part from the front and the second from the back,
    // swapping only a pair that is on the wrong sides.
    for (;;) {
        while (first.end < second.begin && goes_first(refs_[first.end]))
            first.centres.add_point(refs_[first.end++].centre);
        while (first.end < second.begin && !goes_first(refs_[second.begin - 1]))
            second.centres.add_point(refs_[--second.begin].centre);
        if (first.end == second.begin) break;
        std::swap(refs_[first.end], refs_[second.begin - 1]);
    }
    return {first, second};
}

void Builder::make_leaf(std::size_t node, const Range& range) {
    nodes_[node].offset = range.begin;
    nodes_[node].count = static_cast<std::uint16_t>(range.count());
}

Builder::SahSplit Builder::sah_split(const Range& range, int axis, double extent) {
    // Fewer bins for fewer primitives: the bins' fixed cost dominates small nodes.
    const std::size_t bin_count = std::min<std::size_t>(kBins, range.count());
    // Count the primitives and grow the box of each bin of centres along the axis. Bins are
    // found in float, the same way here and in the partition below.
    const float origin = range.centres.lo[axis];
    const auto scale = static_cast<float>(static_cast<double>(bin_count) / extent);
    const auto last = static_cast<float>(bin_count - 1);
    auto bin_of = [&](const Reference& r) {
        const float b = (r.centre[axis] - origin) * scale;  // >= 0
        // NaN (0 * inf for a very thin range) goes to the last bin. Through int: a float's
        // conversion to an unsigned 64-bit type takes a branch.
        return static_cast<std::size_t>(static_cast<int>(b < last ? b : last));
    };
    std::array<Bin, kBins> bins;
    for (std::uint32_t i = range.begin; i < range.end; ++i) {
        Bin& bin = bins[bin_of(refs_[i])];
        ++bin.count;
        bin.box.add(refs_[i].box);
    }
    // Sweep from the right for the boxes above each boundary, then from the left: the cost of
    // splitting after bin s is that of visiting both children, weighted by the chance (their
    // area over the parent's) that a ray through the parent enters each.
    std::array<double, kBins> area_above;
    Box above;
    for (std::size_t s = bin_count - 1; s > 0; --s) {
        above.add(bins[s].box);
        area_above[s] = above.half_area();
    }
    SahSplit best;
    std::size_t best_bin = 0;
    Box below;
    std::uint32_t count_below = 0;
    for (std::size_t s = 0; s + 1 < bin_count; ++s) {
        below.add(bins[s].box);
        count_below += bins[s].count;
        const std::uint32_t count_above = range.count() - count_below;
        if (count_below == 0 || count_above == 0) continue;
        const double cost = count_below * below.half_area() + count_above * area_above[s + 1];
        if (cost < best.cost) {
            best.cost = cost;
            best_bin = s;
        }
    }
    best.cost = kTraversalCost + best.cost / range.box.half_area();
    best.found = std::isfinite(best.cost);
    if (!best.found) return best;
    best.children = partition(range, [&](const Reference& r) { return bin_of(r) <= best_bin; });
    for (std::size_t b = 0; b < bin_count; ++b)
        (b <= best_bin ? best.children.first : best.children.second).box.add(bins[b].box);
    return best;
}

void Builder::build_children(std::size_t node, const std::pair<Range, Range>& children, int depth,
                             int threads) {
    const Range& first = children.first;
    const Range& second = children.second;
    if (threads < 2 || second.count() < kParallelBuildMinimum) {
        build(first, depth + 1, threads);
        nodes_[node].offset = static_cast<std::uint32_t>(nodes_.size());
        build(second, depth + 1, threads);
        return;
    }
    // The two children's references are disjoint ranges of refs_, so they can be
    // partitioned at the same time.
    std::vector<BvhNode> second_nodes;
    second_nodes.reserve(2 * std::size_t{second.count()} - 1);
    std::exception_ptr failure;
    {
        std::jthread helper([&] {
            try {
                Builder(refs_, second_nodes).build(second, depth + 1, threads / 2);
            } catch (...) {
                failure = std::current_exception();
            }
        });
        build(first, depth + 1, threads - threads / 2);
    }
    if (failure) std::rethrow_exception(failure);
    const auto base = static_cast<std::uint32_t>(nodes_.size());
    nodes_[node].offset = base;
    for (BvhNode n : second_nodes) {
        if (!n.is_leaf()) n.offset += base;  // a leaf's offset is already a place in refs_
        nodes_.push_back(n);
    }
}

void Builder::build(const Range& range, int depth, int threads) {
    const std::size_t node = nodes_.size();
    nodes_.push_back({});
    for (int k = 0; k < 3; ++k) {
        nodes_[node].bound[k] = range.box.lo[k];
        nodes_[node].bound[3 + k] = range.box.hi[k];
    }
    const std::uint32_t count = range.count();
    if (count == 1) return make_leaf(node, range);

    const Box& c = range.centres;
    const double extent[3] = {static_cast<double>(c.hi[0]) - c.lo[0],
                              static_cast<double>(c.hi[1]) - c.lo[1],
                              static_cast<double>(c.hi[2]) - c.lo[2]};
    const int axis = extent[0] >= extent[1] && extent[0] >= extent[2] ? 0
                     : extent[1] >= extent[2]                         ? 1
                                                                      : 2;
    const bool fits_leaf = count <= Bvh::kMaxLeafSize;
    std::pair<Range, Range> children;
    if (!(extent[axis] > 0)) {
        // All centroids in one place: no split separates them, so a leaf or an even split.
        if (fits_leaf) return make_leaf(node, range);
        const std::uint32_t mid = range.begin + count / 2;
        children = {measured(range.begin, mid), measured(mid, range.end)};
    } else if (depth >= Bvh::kMaxSahDepth || !std::isfinite(extent[axis])) {
        children = median_split(range, axis);
    } else {
        const auto sah = sah_split(range, axis, extent[axis]);
        if (fits_leaf && !(sah.cost < count)) return make_leaf(node, range);
        // Every centroid in one bin, or areas beyond a double: split evenly.
        children = sah.found ? sah.children : median_split(range, axis);
    }
    build_children(node, children, depth, threads);
}

}  // namespace

BoxRay::BoxRay(const Ray& ray) {
    for (int k = 0; k < 3; ++k) {
        origin_[k] = ray.origin[k];
        inverse_[k] = 1 / ray.direction[k];  // +-inf for a zero component: see enters()
        const bool negative = std::signbit(inverse_[k]);
        near_bound_[k] = negative ? 3 + k : k;
        far_bound_[k] = negative ? k : 3 + k;
    }
}

// Collapses the binary tree below an interior node into wide nodes, depth first: the node's
// two children, then repeatedly the interior child of largest surface area opened into its
// two, until there are four or only leaves. Returns the wide node's index.
std::uint32_t Bvh::collapse_below(std::uint32_t binary) {
    const auto index = static_cast<std::uint32_t>(wide_.size());
    wide_.emplace_back();
    std::uint32_t children[WideNode::kWidth] = {binary + 1, nodes_[binary].offset};
    int size = 2;
    auto half_area = [&](std::uint32_t n) {
        const float* b = nodes_[n].bound;
        double d[3];
        for (int k = 0; k < 3; ++k) d[k] = static_cast<double>(b[3 + k]) - b[k];
        return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
    };
    while (size < WideNode::kWidth) {
        int widest = -1;
        double widest_area = -1;
        for (int i = 0; i < size; ++i) {
            if (nodes_[children[i]].is_leaf()) continue;
            const double area = half_area(children[i]);
            // Not finite (boxes beyond float range) counts as the widest.
            if (widest < 0 || !(area <= widest_area)) {
                widest = i;
                widest_area = area;
            }
        }
        if (widest < 0) break;
        const std::uint32_t opened = children[widest];
        children[widest] = opened + 1;
        children[size++] = nodes_[opened].offset;
    }
    WideNode node{};
    for (int row = 0; row < 3; ++row)
        for (float& v : node.box[row]) v = HUGE_VALF;
    for (int row = 3; row < 6; ++row)
        for (float& v : node.box[row]) v = -HUGE_VALF;
    node.size = static_cast<std::uint8_t>(size);
    for (int i = 0; i < size; ++i) {
        const BvhNode& child = nodes_[children[i]];
        for (int row = 0; row < 6; ++row) node.box[row][i] = child.bound[row];
        if (child.is_leaf()) {
            node.child[i] = child.offset;
            node.count[i] = static_cast<std::uint8_t>(child.count);
        }
    }
    wide_[index] = node;
    // The interior children's nodes follow, each after the subtree before it.
    for (int i = 0; i < size; ++i)
        if (!nodes_[children[i]].is_leaf()) {
            const std::uint32_t below = collapse_below(children[i]);
            wide_[index].child[i] = below;
        }
    return index;
}

void Bvh::collapse() {
    if (nodes_.empty()) return;
    if (!nodes_[0].is_leaf()) {
        collapse_below(0);
    } else {
        // A tree that is one leaf: a wide node with that leaf as its only child.
        WideNode node{};
        for (int row = 0; row < 6; ++row)
            for (float& v : node.box[row]) v = row < 3 ? HUGE_VALF : -HUGE_VALF;
        for (int row = 0; row < 6; ++row) node.box[row][0] = nodes_[0].bound[row];
        node.child[0] = nodes_[0].offset;
        node.count[0] = static_cast<std::uint8_t>(nodes_[0].count);
        node.size = 1;
        wide_.push_back(node);
    }
    wide_.shrink_to_fit();
}

Bvh::Bvh(std::span<const Bounds> boxes, int threads) {
    if (boxes.empty()) return;
    std::vector<Reference> refs;
    refs.reserve(boxes.size());
    for (std::uint32_t i = 0; i < boxes.size(); ++i) refs.push_back(make_reference(boxes[i], i));
    // A binary tree with n leaves has 2n - 1 nodes; reserving them keeps the build from
    // reallocating (pages never touched cost no memory), and the fit afterwards trims it.
    nodes_.reserve(2 * boxes.size() - 1);
    Builder builder(refs, nodes_);
    builder.build(builder.whole(), 0, threads);
    nodes_.shrink_to_fit();
    collapse();
    order_.reserve(refs.size());
    for (const Reference& r : refs) order_.push_back(r.index);
}

}  // namespace rt
