// Building the hierarchy: top down, each node split where the surface area heuristic (SAH),
// evaluated at a few bin boundaries along the centroids' longest axis, says a ray will do
// the least work; nodes are written straight into the flat array in depth-first order.
//
// The build works on a compact copy of the boxes (floats, rounded outward, with the
// primitive's index), partitioned in place, so every pass reads memory in order. One pass per
// node bins the primitives; the bins already hold the children's boxes, so the partition that
// follows is the only other pass. A node of at most 32 primitives is split by a sweep over
// them in order instead, which costs it less than its bins would.
#include "accel/bvh.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <exception>
#include <new>
#include <thread>
#include <type_traits>

#include "accel/parallel.h"

namespace rt {

namespace {

// Bin boundaries per split. More bins find slightly better splits and cost build time.
constexpr int kBins = 16;
// Boxes are widened by this much relative to their coordinates, so that a hit point a
// primitive computes a rounding error outside its exact bounds still lies in its node.
constexpr double kBoxPadding = 1e-9;
// Nodes of at most this many references are split by a sweep over their references sorted
// along the axis, not by bins: a small node's bins cost more than its references.
constexpr std::uint32_t kSmallNode = 32;
static_assert(kSmallNode <= 32);  // build_small gives a reference's place five bits of its key
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

// Four floats as one value (the GCC/clang vector extension: SSE on x86-64, NEON on arm64):
// x, y, z and a fourth lane that boxes carry along and never read.
using Floats = float __attribute__((vector_size(16)));

// Lane by lane std::min(a, b) and std::max(a, b), with their choices where either is NaN, so
// that the boxes are those the scalar build made.
Floats lane_min(Floats a, Floats b) { return b < a ? b : a; }
Floats lane_max(Floats a, Floats b) { return a < b ? b : a; }

// A box of floats; empty (lo > hi) until something is added.
struct Box {
    Floats lo = {HUGE_VALF, HUGE_VALF, HUGE_VALF, HUGE_VALF};
    Floats hi = {-HUGE_VALF, -HUGE_VALF, -HUGE_VALF, -HUGE_VALF};

    void add(const Box& b) {
        lo = lane_min(lo, b.lo);
        hi = lane_max(hi, b.hi);
    }
    void add_point(Floats p) {
        lo = lane_min(lo, p);
        hi = lane_max(hi, p);
    }
    // In double: a float box's sides can overflow a float product.
    double half_area() const {
        if (!(lo[0] <= hi[0])) return 0;
        double d[3];
        for (int k = 0; k < 3; ++k) d[k] = static_cast<double>(hi[k]) - lo[k];
        return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
    }
};

// One primitive as the build sees it: its box, the box's centre, and in the centre's fourth
// place the primitive's index (its bits), which the centres' boxes carry along unread. The
// box's fourth lanes hold, once it is binned, the reference's bin in its range's plan (lo),
// which the partition then reads instead of finding it again.
struct Reference {
    // The box's corners (Box's lanes), as plain vectors: a trivial type, so that an array of
    // references can be allocated without being written (parallel.h).
    Floats lo, hi;
    float centre[4];

    Box box() const { return {lo, hi}; }

    Floats centre_lanes() const {
        Floats v;
        std::memcpy(&v, centre, sizeof v);
        return v;
    }
    std::uint32_t index() const { return std::bit_cast<std::uint32_t>(centre[3]); }
    float bin() const { return lo[3]; }
    // Through int: converting a 64-bit unsigned value to float takes a branch.
    void set_bin(std::size_t b) { lo[3] = static_cast<float>(static_cast<int>(b)); }
};
static_assert(sizeof(Reference) == 48);
static_assert(std::is_trivially_default_constructible_v<Reference>);
using References = std::vector<Reference, UninitializedAllocator<Reference>>;

Reference make_reference(const Bounds& b, std::uint32_t index) {
    const double pad =
        kBoxPadding * (1 + max_of_magnitudes(max_abs_component(b.min), max_abs_component(b.max)));
    Reference r{};
    for (int k = 0; k < 3; ++k) {
        r.lo[k] = float_below(b.min[k] - pad);
        r.hi[k] = float_above(b.max[k] + pad);
        // Halves first: min + max can overflow where neither does.
        r.centre[k] = static_cast<float>(std::clamp(b.min[k] * 0.5 + b.max[k] * 0.5,
                                                    static_cast<double>(-FLT_MAX),
                                                    static_cast<double>(FLT_MAX)));
    }
    r.lo[3] = 0;
    r.hi[3] = 0;
    r.centre[3] = std::bit_cast<float>(index);
    return r;
}

// A range of references with the box of their boxes and the box of their centres.
struct Range {
    std::uint32_t begin, end;
    Box box, centres;

    std::uint32_t count() const { return end - begin; }
};

// The centres' extent along each axis, in double, and the longest axis (the first of equals).
struct Spread {
    double extent[3];
    int axis;

    explicit Spread(const Box& c)
        : extent{static_cast<double>(c.hi[0]) - c.lo[0], static_cast<double>(c.hi[1]) - c.lo[1],
                 static_cast<double>(c.hi[2]) - c.lo[2]},
          axis(extent[0] >= extent[1] && extent[0] >= extent[2] ? 0
               : extent[1] >= extent[2]                         ? 1
                                                                : 2) {}
};

// How a range's centres are put into bins along its longest axis for its SAH split. Bins are
// found in float, the same way when binning and when partitioning.
struct BinPlan {
    int axis = 0;
    std::size_t count = 0;  // bins in use; 0 when the range takes no SAH split
    float origin = 0, scale = 0, last = 0;

    std::size_t bin_of(const Reference& r) const {
        const float b = (r.centre[axis] - origin) * scale;  // >= 0
        // NaN (0 * inf for a very thin range) goes to the last bin. Through int: a float's
        // conversion to an unsigned 64-bit type takes a branch.
        return static_cast<std::size_t>(static_cast<int>(b < last ? b : last));
    }
};

struct Bin {
    std::uint32_t count = 0;
    Box box, centres;

    void add(const Reference& r) {
        ++count;
        box.add(r.box());
        centres.add_point(r.centre_lanes());
    }
};

// A range's references in the bins of its plan. Only the plan's bins are set (reset()): a
// node makes two of these, and most nodes are small.
struct Binned {
    BinPlan plan;
    union {
        Bin bins[kBins];
    };

    Binned() {}
    void reset(const BinPlan& p) {
        plan = p;
        for (std::size_t b = 0; b < plan.count; ++b) new (&bins[b]) Bin;
    }
};
static_assert(std::is_trivially_destructible_v<Bin>);

class Builder {
  public:
    // `spare` counts the threads that may still be started (shared by every builder of one
    // tree, and lent back by a thread while it waits for another).
    // `node_cost`: visiting a node, relative to testing one primitive (Bvh's constructor).
    Builder(References& refs, Bvh::Nodes& nodes, std::atomic<int>& spare, double node_cost)
        : refs_(refs), nodes_(nodes), spare_(spare), node_cost_(node_cost) {}

    Range whole() const { return measured(0, static_cast<std::uint32_t>(refs_.size())); }
    // Writes the subtree over the range into nodes_, depth first. Where a spare thread is
    // free, it builds a large node's second child into nodes of its own, appended
    // afterwards, so the array is the same however many threads built it, and whichever
    // did. `binned`, when given, is the range already in the bins of its plan (its parent's
    // partition put them there), so that each level reads the references once, not twice.
    void build(const Range& range, const Binned* binned, int depth);

  private:
    struct SahSplit {
        double cost = kInfinity;     // relative to testing one primitive
        bool found = false;          // false when no boundary separates the primitives
        std::size_t last_first = 0;  // the last bin whose references go to the first child
    };
    struct Children {
        Range first, second;
        Binned first_bins, second_bins;  // plan.count 0 where a child takes no SAH split
    };

    // The plan of a range at a depth: none (count 0) where build() splits it otherwise.
    BinPlan plan_for(const Range& range, int depth) const;
    // Whether a node of `count` references is a leaf whatever its split: its SAH cost as a
    // leaf (count) is at most the node cost, which any split's cost exceeds or equals. Its
    // references are then not binned (by its parent) nor priced.
    bool surely_leaf(std::uint32_t count) const {
        return count <= Bvh::kMaxLeafSize && count <= node_cost_;
    }
    void bin(const Range& range, Binned& binned);
    SahSplit best_split(const Range& range, const Binned& binned) const;
    // Moves the references of the bins up to split.last_first to the front of the range,
    // putting each in its child's bins on the way; the children's boxes come from the bins.
    void partition(const Range& range, const Binned& binned, const SahSplit& split, int depth,
                   Children& children);

    Range measured(std::uint32_t begin, std::uint32_t end) const;
    // Splits in the middle of the range, for primitives no position separates.
    std::pair<Range, Range> median_split(const Range& range, int axis);
    void make_leaf(std::size_t node, const Range& range);
    // The SAH split of a small node (at most kSmallNode references) by a sweep over its
    // references in order along the axis; a leaf where that is cheaper.
    void build_small(std::size_t node, const Range& range, int axis, int depth);
    void build_children(std::size_t node, const Range& first, const Binned* first_bins,
                        const Range& second, const Binned* second_bins, int depth);
    // Takes a spare thread if there is one.
    bool take_spare();

    References& refs_;
    Bvh::Nodes& nodes_;
    std::atomic<int>& spare_;
    double node_cost_;
};

bool Builder::take_spare() {
    int n = spare_.load();
    while (n > 0 && !spare_.compare_exchange_weak(n, n - 1)) {
    }
    return n > 0;
}

Range Builder::measured(std::uint32_t begin, std::uint32_t end) const {
    Range r{begin, end, {}, {}};
    for (std::uint32_t i = begin; i < end; ++i) {
        r.box.add(refs_[i].box());
        r.centres.add_point(refs_[i].centre_lanes());
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

void Builder::make_leaf(std::size_t node, const Range& range) {
    nodes_[node].offset = range.begin;
    nodes_[node].count = static_cast<std::uint16_t>(range.count());
}

BinPlan Builder::plan_for(const Range& range, int depth) const {
    BinPlan plan;
    if (range.count() <= kSmallNode || depth >= Bvh::kMaxSahDepth || surely_leaf(range.count()))
        return plan;
    const Spread spread(range.centres);
    const double extent = spread.extent[spread.axis];
    if (!(extent > 0) || !std::isfinite(extent)) return plan;
    // Fewer bins for fewer primitives: the bins' fixed cost dominates small nodes.
    plan.count = std::min<std::size_t>(kBins, range.count());
    plan.axis = spread.axis;
    plan.origin = range.centres.lo[spread.axis];
    plan.scale = static_cast<float>(static_cast<double>(plan.count) / extent);
    plan.last = static_cast<float>(plan.count - 1);
    return plan;
}

void Builder::bin(const Range& range, Binned& binned) {
    Reference* const refs = refs_.data();
    const BinPlan plan = binned.plan;  // a copy: the bins' stores cannot change it
    for (std::uint32_t i = range.begin; i < range.end; ++i) {
        const std::size_t b = plan.bin_of(refs[i]);
        binned.bins[b].add(refs[i]);
        refs[i].set_bin(b);  // after the add's loads: see put() in partition()
    }
}

Builder::SahSplit Builder::best_split(const Range& range, const Binned& binned) const {
    const std::size_t bin_count = binned.plan.count;
    const Bin* const bins = binned.bins;
    // Sweep from the right for the boxes above each boundary, then from the left: the cost of
    // splitting after bin s is that of visiting both children, weighted by the chance (their
    // area over the parent's) that a ray through the parent enters each.
    // An empty bin adds nothing: the boundary after it splits as the one before it does, at
    // the same cost, and the first of equal costs is kept, so it is skipped (a small node
    // has as many bins as references, and about a third of them are empty).
    std::array<double, kBins> area_above;
    Box above;
    for (std::size_t s = bin_count - 1; s > 0; --s) {
        if (bins[s].count == 0) {
            area_above[s] = s + 1 < bin_count ? area_above[s + 1] : 0;
            continue;
        }
        above.add(bins[s].box);
        area_above[s] = above.half_area();
    }
    SahSplit best;
    Box below;
    std::uint32_t count_below = 0;
    for (std::size_t s = 0; s + 1 < bin_count; ++s) {
        if (bins[s].count == 0) continue;
        below.add(bins[s].box);
        count_below += bins[s].count;
        const std::uint32_t count_above = range.count() - count_below;
        if (count_above == 0) continue;
        const double cost = count_below * below.half_area() + count_above * area_above[s + 1];
        if (cost < best.cost) {
            best.cost = cost;
            best.last_first = s;
        }
    }
    best.cost = node_cost_ + best.cost / range.box.half_area();
    best.found = std::isfinite(best.cost);
    return best;
}

void Builder::partition(const Range& range, const Binned& binned, const SahSplit& split, int depth,
                        Children& children) {
    // The children as the bins give them, before a reference moves.
    Range& first = children.first;
    Range& second = children.second;
    first = {range.begin, range.begin, {}, {}};
    second = {range.end, range.end, {}, {}};
    for (std::size_t b = 0; b < binned.plan.count; ++b) {
        const Bin& bin = binned.bins[b];
        Range& child = b <= split.last_first ? first : second;
        child.box.add(bin.box);
        child.centres.add(bin.centres);
        if (b <= split.last_first) first.end += bin.count;
    }
    second.begin = first.end;
    children.first_bins.reset(plan_for(first, depth + 1));
    children.second_bins.reset(plan_for(second, depth + 1));
    // Hoare's scheme: grow the first part from the front and the second from the back,
    // swapping only a pair that is on the wrong sides; each reference goes into its child's
    // bins when its side is settled. On local copies of the plans: the stores cannot then be
    // taken to change them.
    Reference* const refs = refs_.data();
    const BinPlan first_plan = children.first_bins.plan;
    const BinPlan second_plan = children.second_bins.plan;
    // Every reference of the range holds its bin (set when it was binned); bins are small
    // whole numbers, exact in float.
    const auto last_first = static_cast<float>(split.last_first);
    const auto goes_first = [last_first](const Reference& r) { return r.bin() <= last_first; };
    const auto put = [](const BinPlan& plan, Bin* bins, Reference& r) {
        if (plan.count == 0) return;
        const std::size_t b = plan.bin_of(r);
        // The add first: a 4-byte store into the box followed by a 16-byte load of it
        // cannot be forwarded from the store buffer, and that stall was a third of the build.
        bins[b].add(r);
        r.set_bin(b);
    };
    Bin* const first_bins = children.first_bins.bins;
    Bin* const second_bins = children.second_bins.bins;
    std::uint32_t front = range.begin, back = range.end;
    // Blocks first (Edelkamp and Weiss's BlockQuicksort): each side notes, without a branch,
    // which of its next kBlock references belong on the other side, and those are swapped in
    // pairs. Hoare's loop below branches on every reference's side, which at most levels
    // is a coin toss the processor mispredicts half the time. The swaps only reorder
    // references within a child, whose bins (and so the tree) do not depend on that order.
    constexpr std::uint32_t kBlock = 64;
    std::uint8_t misplaced_front[kBlock], misplaced_back[kBlock];
    std::uint32_t front_count = 0, front_done = 0, back_count = 0, back_done = 0;
    while (back - front >= 2 * kBlock) {
        if (front_count == front_done) {
            front_count = front_done = 0;
            for (std::uint32_t i = 0; i < kBlock; ++i) {
                misplaced_front[front_count] = static_cast<std::uint8_t>(i);
                front_count += goes_first(refs[front + i]) ? 0 : 1;
            }
        }
        if (back_count == back_done) {
            back_count = back_done = 0;
            for (std::uint32_t i = 0; i < kBlock; ++i) {
                misplaced_back[back_count] = static_cast<std::uint8_t>(i);
                back_count += goes_first(refs[back - 1 - i]) ? 1 : 0;
            }
        }
        const std::uint32_t pairs = std::min(front_count - front_done, back_count - back_done);
        for (std::uint32_t k = 0; k < pairs; ++k)
            std::swap(refs[front + misplaced_front[front_done + k]],
                      refs[back - 1 - misplaced_back[back_done + k]]);
        front_done += pairs;
        back_done += pairs;
        // A block whose misplaced references have all gone is settled: into the bins.
        if (front_count == front_done) {
            for (std::uint32_t i = 0; i < kBlock; ++i) put(first_plan, first_bins, refs[front + i]);
            front += kBlock;
        }
        if (back_count == back_done) {
            for (std::uint32_t i = 0; i < kBlock; ++i)
                put(second_plan, second_bins, refs[back - 1 - i]);
            back -= kBlock;
        }
    }
    // What is left (under two blocks, and a block not yet settled) by Hoare's loop.
    for (;;) {
        while (front < back && goes_first(refs[front])) {
            put(first_plan, first_bins, refs[front++]);
        }
        while (front < back && !goes_first(refs[back - 1])) {
            put(second_plan, second_bins, refs[--back]);
        }
        if (front == back) break;
        std::swap(refs[front], refs[back - 1]);
    }
}

void Builder::build_small(std::size_t node, const Range& range, int axis, int depth) {
    const std::uint32_t count = range.count();
    Reference* const refs = refs_.data() + range.begin;
    // The references' places in order along the axis, without a branch: each reference's
    // rank is how many keys are below its own. A key is its centre as an integer whose order
    // is the float's, the lowest five bits given to its place in the range, so that no two
    // keys are equal and the ranks are a permutation, even for NaN.
    std::int32_t exact[kSmallNode], key[kSmallNode];
    for (std::uint32_t i = 0; i < count; ++i) {
        const auto bits = std::bit_cast<std::int32_t>(refs[i].centre[axis]);
        exact[i] = bits ^ ((bits >> 31) & 0x7fffffff);
        key[i] = (exact[i] & ~std::int32_t{31}) | static_cast<std::int32_t>(i);
    }
    std::uint8_t order[kSmallNode];
    std::int32_t in_order[kSmallNode];  // exact[order[s]]
    for (std::uint32_t i = 0; i < count; ++i) {
        std::uint32_t rank = 0;
        for (std::uint32_t j = 0; j < count; ++j) rank += key[j] < key[i] ? 1 : 0;
        order[rank] = static_cast<std::uint8_t>(i);
        in_order[rank] = exact[i];
    }
    // Centres within 32 units in the last place of each other were ranked by their places:
    // the rare pair left out of order is moved by insertion, so that every split below parts
    // the centres by position.
    for (std::uint32_t s = 1; s < count; ++s) {
        if (!(in_order[s] < in_order[s - 1])) continue;
        const std::uint8_t moving = order[s];
        const std::int32_t moving_key = in_order[s];
        std::uint32_t j = s;
        for (; j > 0 && moving_key < in_order[j - 1]; --j) {
            order[j] = order[j - 1];
            in_order[j] = in_order[j - 1];
        }
        order[j] = moving;
        in_order[j] = moving_key;
    }
    // As best_split: the boxes above each place from the right, then the cost of each split
    // from the left; the first of equal costs wins.
    std::array<double, kSmallNode> area_above;
    Box above;
    for (std::uint32_t s = count - 1; s > 0; --s) {
        above.add(refs[order[s]].box());
        area_above[s] = above.half_area();
    }
    double best_cost = kInfinity;
    std::uint32_t best_first = 0;  // references going to the first child
    Box below;
    for (std::uint32_t s = 0; s + 1 < count; ++s) {
        below.add(refs[order[s]].box());
        // Not between equal centres, which bins never part either.
        if (!(refs[order[s]].centre[axis] < refs[order[s + 1]].centre[axis])) continue;
        const double cost = (s + 1) * below.half_area() + (count - s - 1) * area_above[s + 1];
        if (cost < best_cost) {
            best_cost = cost;
            best_first = s + 1;
        }
    }
    best_cost = node_cost_ + best_cost / range.box.half_area();
    if (count <= Bvh::kMaxLeafSize && !(best_cost < count)) return make_leaf(node, range);
    if (!std::isfinite(best_cost)) {
        const auto [first, second] = median_split(range, axis);
        return build_children(node, first, nullptr, second, nullptr, depth);
    }
    Reference sorted[kSmallNode];
    for (std::uint32_t i = 0; i < count; ++i) sorted[i] = refs[order[i]];
    std::memcpy(refs, sorted, count * sizeof(Reference));
    const std::uint32_t middle = range.begin + best_first;
    build_children(node, measured(range.begin, middle), nullptr, measured(middle, range.end),
                   nullptr, depth);
}

void Builder::build_children(std::size_t node, const Range& first, const Binned* first_bins,
                             const Range& second, const Binned* second_bins, int depth) {
    if (second.count() < kParallelBuildMinimum || !take_spare()) {
        build(first, first_bins, depth + 1);
        nodes_[node].offset = static_cast<std::uint32_t>(nodes_.size());
        build(second, second_bins, depth + 1);
        return;
    }
    // The two children's references are disjoint ranges of refs_, so they can be
    // partitioned at the same time.
    Bvh::Nodes second_nodes;
    second_nodes.reserve(2 * std::size_t{second.count()} - 1);
    std::exception_ptr failure;
    {
        std::jthread helper([&] {
            try {
                Builder(refs_, second_nodes, spare_, node_cost_)
                    .build(second, second_bins, depth + 1);
            } catch (...) {
                failure = std::current_exception();
            }
            ++spare_;
        });
        build(first, first_bins, depth + 1);
        // While this thread waits, the helper (or a thread it starts) may use it: a split
        // that is far from even then keeps both cores busy.
        ++spare_;
        helper.join();
        --spare_;
    }
    if (failure) std::rethrow_exception(failure);
    const auto base = static_cast<std::uint32_t>(nodes_.size());
    nodes_[node].offset = base;
    for (BvhNode n : second_nodes) {
        if (!n.is_leaf()) n.offset += base;  // a leaf's offset is already a place in refs_
        nodes_.push_back(n);
    }
}

void Builder::build(const Range& range, const Binned* binned, int depth) {
    const std::size_t node = nodes_.size();
    nodes_.push_back({});
    for (int k = 0; k < 3; ++k) {
        nodes_[node].bound[k] = range.box.lo[k];
        nodes_[node].bound[3 + k] = range.box.hi[k];
    }
    const std::uint32_t count = range.count();
    if (count == 1) return make_leaf(node, range);

    const bool fits_leaf = count <= Bvh::kMaxLeafSize;
    Binned own;
    if (binned == nullptr) {
        // A node its parent planned (binned) passed these checks in plan_for already.
        const Spread spread(range.centres);
        const double extent = spread.extent[spread.axis];
        if (!(extent > 0)) {
            // All centroids in one place: no split separates them, so a leaf or an even split.
            if (fits_leaf) return make_leaf(node, range);
            const std::uint32_t mid = range.begin + count / 2;
            return build_children(node, measured(range.begin, mid), nullptr,
                                  measured(mid, range.end), nullptr, depth);
        }
        if (depth >= Bvh::kMaxSahDepth || !std::isfinite(extent)) {
            const auto [first, second] = median_split(range, spread.axis);
            return build_children(node, first, nullptr, second, nullptr, depth);
        }
        // At node cost 2 (a mesh, or spheres only) that is every node of two references.
        if (surely_leaf(count)) return make_leaf(node, range);
        if (count <= kSmallNode) return build_small(node, range, spread.axis, depth);
        own.reset(plan_for(range, depth));
        bin(range, own);
        binned = &own;
    }
    const SahSplit split = best_split(range, *binned);
    // A leaf is not partitioned: the order of the references within a leaf changes no
    // answer (ties are judged by the object's place in the file, not the leaf's), and half
    // the nodes are leaves.
    if (fits_leaf && !(split.cost < count)) return make_leaf(node, range);
    if (!split.found) {
        // Every centroid in one bin, or areas beyond a double: split evenly.
        const auto [first, second] = median_split(range, binned->plan.axis);
        return build_children(node, first, nullptr, second, nullptr, depth);
    }
    Children children;
    partition(range, *binned, split, depth, children);
    const auto pre = [](const Binned& b) { return b.plan.count > 0 ? &b : nullptr; };
    build_children(node, children.first, pre(children.first_bins), children.second,
                   pre(children.second_bins), depth);
}

}  // namespace

// The children a wide node takes in place of an interior binary node: the node's two
// children, then repeatedly the interior child of largest surface area opened into its two,
// until there are WideNode::kWidth (eight) or only leaves. Returns how many.
int Bvh::wide_children(std::uint32_t binary, std::uint32_t (&children)[WideNode::kWidth]) const {
    children[0] = binary + 1;
    children[1] = nodes_[binary].offset;
    int size = 2;
    while (size < WideNode::kWidth) {
        int widest = -1;
        double widest_area = -1;
        for (int i = 0; i < size; ++i) {
            if (nodes_[children[i]].is_leaf()) continue;
            const double area = bound_half_area(nodes_[children[i]].bound);
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
    return size;
}

std::size_t Bvh::wide_count_below(std::uint32_t binary) const {
    std::uint32_t children[WideNode::kWidth];
    const int size = wide_children(binary, children);
    std::size_t count = 1;
    for (int i = 0; i < size; ++i)
        if (!nodes_[children[i]].is_leaf()) count += wide_count_below(children[i]);
    return count;
}

// The wide node over the given binary children: their boxes side by side, and for each leaf
// its primitives; an interior child's index is left for the caller.
WideNode Bvh::wide_node(const std::uint32_t (&children)[WideNode::kWidth], int size) const {
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
    return node;
}

// Writes the wide node of an interior binary node at wide_[index] and the wide nodes of its
// interior children's subtrees after it, depth first, each after the subtree before it.
// Returns the index after the last node written.
std::uint32_t Bvh::collapse_into(std::uint32_t binary, std::uint32_t index) {
    std::uint32_t children[WideNode::kWidth];
    const int size = wide_children(binary, children);
    WideNode node = wide_node(children, size);
    std::uint32_t next = index + 1;
    for (int i = 0; i < size; ++i)
        if (!nodes_[children[i]].is_leaf()) {
            node.child[i] = next;
            next = collapse_into(children[i], next);
        }
    wide_[index] = node;
    return next;
}

std::vector<Bounds> Bvh::outline(std::size_t at_most) const {
    std::vector<Bounds> boxes;
    if (wide_.empty()) return boxes;
    const auto box_of = [](const WideNode& node, int lane) {
        const std::array<float, 6> b = node.bound(lane);
        return Bounds{{b[0], b[1], b[2]}, {b[3], b[4], b[5]}};
    };
    // Level by level: the leaves met so far, and the wide nodes whose children are the rest.
    std::vector<std::uint32_t> level{0}, next;
    for (;;) {
        // The cut's size here and one level down (the same where every child is a leaf).
        std::size_t here = boxes.size(), deeper = boxes.size();
        for (const std::uint32_t n : level)
            for (int i = 0; i < wide_[n].size; ++i) {
                ++here;
                deeper += wide_[n].is_leaf(i) ? 1 : wide_[wide_[n].child[i]].size;
            }
        if (deeper == here || deeper > at_most) break;
        next.clear();
        for (const std::uint32_t n : level)
            for (int i = 0; i < wide_[n].size; ++i) {
                if (wide_[n].is_leaf(i))
                    boxes.push_back(box_of(wide_[n], i));
                else
                    next.push_back(wide_[n].child[i]);
            }
        level.swap(next);
    }
    for (const std::uint32_t n : level)
        for (int i = 0; i < wide_[n].size; ++i) boxes.push_back(box_of(wide_[n], i));
    return boxes;
}

void Bvh::collapse(int threads) {
    if (nodes_.empty()) return;
    if (nodes_[0].is_leaf()) {
        // A tree that is one leaf: a wide node with that leaf as its only child.
        const std::uint32_t only[WideNode::kWidth] = {0};
        wide_.push_back(wide_node(only, 1));
        return;
    }
    // Below this many binary nodes a thread costs more than it saves.
    constexpr std::size_t kParallelCollapseMinimum = 65536;
    if (threads <= 1 || nodes_.size() < kParallelCollapseMinimum) {
        // One thread writes the whole tree depth first into an array of the largest size it
        // can need (every wide node takes the place of at least one interior binary node;
        // pages never written cost no memory), then cut to what it wrote: no count first.
        wide_.resize((nodes_.size() - 1) / 2);
        wide_.resize(collapse_into(0, 0));
        return;
    }
    // On several threads the root's interior children's subtrees are counted first (on the
    // threads too), so that each subtree's place is known and they can be written at once,
    // into an array allocated at its size, whose pages they are the first to touch.
    std::uint32_t children[WideNode::kWidth];
    const int size = wide_children(0, children);
    WideNode root = wide_node(children, size);
    std::uint32_t subtrees[WideNode::kWidth], places[WideNode::kWidth];
    std::size_t counts[WideNode::kWidth];
    int interior = 0;
    for (int i = 0; i < size; ++i)
        if (!nodes_[children[i]].is_leaf()) subtrees[interior++] = children[i];
    const auto each_subtree = [&](auto&& body) {
        parallel_parts(static_cast<std::size_t>(interior), threads, 1,
                       [&](std::size_t begin, std::size_t end) {
                           for (std::size_t k = begin; k < end; ++k) body(k);
                       });
    };
    each_subtree([&](std::size_t k) { counts[k] = wide_count_below(subtrees[k]); });
    std::size_t total = 1;
    for (int i = 0, k = 0; i < size; ++i)
        if (!nodes_[children[i]].is_leaf()) {
            root.child[i] = places[k] = static_cast<std::uint32_t>(total);
            total += counts[k++];
        }
    wide_.resize(total);
    wide_[0] = root;
    each_subtree([&](std::size_t k) { collapse_into(subtrees[k], places[k]); });
}

Bvh::Bvh(std::size_t count, BoundsSource source, int threads, double node_cost) {
    if (count == 0) return;
    // Below this many per thread, starting threads costs more than the loops save.
    constexpr std::size_t kPart = 65536;
    References refs(count);
    parallel_parts(count, threads, kPart, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const auto index = static_cast<std::uint32_t>(i);
            refs[i] = make_reference(source.bounds(source.context, index), index);
        }
    });
    // A binary tree with n leaves has 2n - 1 nodes; reserving them keeps the build from
    // reallocating, and pages never touched cost no memory. The array is not trimmed after:
    // that would copy it, and its owners free it once it is collapsed (drop_binary_nodes).
    nodes_.reserve(2 * count - 1);
    std::atomic<int> spare = std::max(threads, 1) - 1;
    Builder builder(refs, nodes_, spare, node_cost);
    builder.build(builder.whole(), nullptr, 0);
    collapse(threads);
    order_.resize(refs.size());
    parallel_parts(refs.size(), threads, kPart, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) order_[i] = refs[i].index();
    });
}

}  // namespace rt
