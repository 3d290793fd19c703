// A bounding volume hierarchy over boxes, written once and used twice: over the scene's
// objects (object_index.h) and over the triangles inside a mesh. It knows nothing of what
// the boxes hold: traversal calls back with each candidate's place in leaf order.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

#include "accel/parallel.h"
#include "rt/ray.h"

// The eight-lane walk for AVX2 is compiled beside the portable one on x86-64 (by g++ and
// clang alike) and chosen at run time; elsewhere there is only the portable one.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define RT_AVX2_PATH 1
#else
#define RT_AVX2_PATH 0
#endif

namespace rt {

#if RT_AVX2_PATH
// Whether this processor has AVX2, asked once.
inline const bool kHasAvx2 = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
}();
#endif

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

// Half the surface area of a box laid out as a node's bound (min x, y, z, then max): the
// SAH's measure of how likely a ray through a parent enters it. In double: a float box's
// sides can overflow a float product.
inline double bound_half_area(const float bound[6]) {
    double d[3];
    for (int k = 0; k < 3; ++k) d[k] = static_cast<double>(bound[3 + k]) - bound[k];
    return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
}

// A ray prepared for many box tests: the reciprocal of its direction, and for each axis which
// of a node's two bounds the ray meets first.
class BoxRay {
  public:
    explicit BoxRay(const Ray& ray) {
        for (int k = 0; k < 3; ++k) {
            origin_[k] = ray.origin[k];
            inverse_[k] = 1 / ray.direction[k];  // +-inf for a zero component: see enters()
            const bool negative = std::signbit(inverse_[k]);
            near_bound_[k] = negative ? 3 + k : k;
            far_bound_[k] = negative ? k : 3 + k;
        }
    }

    // Whether the ray passes through the node's box somewhere in [t_min, t_max]; if so,
    // t_enter is where (from t_min on) it enters. The range starts as [t_min, t_max], each
    // slab narrows it, and the result is widened by a relative margin so that a hit a
    // primitive computes at the box's very edge, or at exactly t_max (a tie), is never
    // pruned. A ray parallel to a slab whose origin lies on the slab's plane makes 0 * inf =
    // NaN there; the comparisons below then ignore that slab, which only keeps more.
    bool enters(const BvhNode& node, double t_min, double t_max, double& t_enter) const {
        return enters(node.bound, t_min, t_max, t_enter);
    }
    bool enters(const float bound[6], double t_min, double t_max, double& t_enter) const {
        double near = t_min, far = t_max;
        for (int k = 0; k < 3; ++k) {
            const double slab_near = (bound[near_bound_[k]] - origin_[k]) * inverse_[k];
            const double slab_far = (bound[far_bound_[k]] - origin_[k]) * inverse_[k];
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

// One node of the wide tree that traversal walks: up to eight children, whose boxes lie side
// by side (structure of arrays) so that one ray is tested against several at once. 256
// bytes, four cache lines. The wide tree is the binary tree above collapsed: each wide node
// takes the place of up to seven binary interior nodes, and its children are the binary
// nodes below them, so the leaves and their order are the binary tree's. Eight rather than
// four: a query visits fewer nodes, each a load that waits for the test before it
// (docs/performance.md, "Eight children per node").
struct alignas(64) WideNode {
    static constexpr int kWidth = 8;
    // box[k][i] for k < 3 is child i's min corner along axis k, box[3 + k][i] its max; floats
    // copied from the binary nodes (already rounded outward). Unused lanes hold an empty box.
    float box[6][kWidth];
    // A leaf child's first primitive in leaf order, or an interior child's wide node index.
    std::uint32_t child[kWidth];
    std::uint8_t count[kWidth];  // a leaf child's primitives; 0 for an interior child
    std::uint8_t size;           // children in use, from the first lane on
    std::uint8_t unused[23];     // zero: no padding of undefined value, so nodes compare bytewise

    bool is_leaf(int i) const { return count[i] != 0; }
    // Child i's box laid out as a binary node's (min x, y, z, then max), for the double test.
    std::array<float, 6> bound(int i) const {
        return {box[0][i], box[1][i], box[2][i], box[3][i], box[4][i], box[5][i]};
    }
};
static_assert(sizeof(WideNode) == 256);
static_assert(std::is_trivially_default_constructible_v<WideNode>);
static_assert(WideNode::kWidth == 8, "the vector code below tests four or eight lanes at once");

// The vector types of the float box test, four or eight lanes of 32 bits.
template <int Lanes>
struct LaneVectors;
template <>
struct LaneVectors<4> {
    using Floats = float __attribute__((vector_size(16)));
    using Ints = std::int32_t __attribute__((vector_size(16)));
};
template <>
struct LaneVectors<8> {
    using Floats = float __attribute__((vector_size(32)));
    using Ints = std::int32_t __attribute__((vector_size(32)));
};

// Each lane's sign bit as bit i of a number. A node's walk waits for this mask before it can
// branch, and gathered lane by lane (an extract and an OR each) it was a chain of some
// fifteen instructions; on x86-64 it is one, movmskps (SSE, in every x86-64 build; its
// eight-lane form needs AVX, so only the AVX2 walk asks for it, with Avx2). Renders took
// 0.90-0.99 of the time (docs/performance.md, "The lanes' mask in one instruction").
// Eight lanes elsewhere on x86-64 take two. On arm64 the lanes are gathered one by one, to
// the same bits.
#if RT_AVX2_PATH
[[gnu::target("avx2")]] inline unsigned sign_bits_avx2(const LaneVectors<8>::Ints& lanes) {
    return static_cast<unsigned>(
        __builtin_ia32_movmskps256(reinterpret_cast<LaneVectors<8>::Floats>(lanes)));
}
#endif
template <int Lanes, bool Avx2>
[[gnu::always_inline]] inline unsigned sign_bits(const typename LaneVectors<Lanes>::Ints& lanes) {
#if RT_AVX2_PATH
    if constexpr (Lanes == 8 && Avx2) {
        return sign_bits_avx2(lanes);
    } else if constexpr (Lanes == 4) {
        return static_cast<unsigned>(
            __builtin_ia32_movmskps(reinterpret_cast<LaneVectors<4>::Floats>(lanes)));
    } else {
        // Eight lanes without AVX: two halves of four, one movmskps each.
        LaneVectors<4>::Ints low, high;
        std::memcpy(&low, &lanes, sizeof low);
        std::memcpy(&high, reinterpret_cast<const char*>(&lanes) + sizeof low, sizeof high);
        return sign_bits<4, false>(low) | sign_bits<4, false>(high) << 4;
    }
#endif
    unsigned bits = 0;
    for (int i = 0; i < Lanes; ++i) bits |= (static_cast<unsigned>(lanes[i]) >> 31) << i;
    return bits;
}

// A ray prepared for testing the boxes of a wide node in float. Float arithmetic only
// culls, so every rounding is taken against culling: the origin is bracketed by the floats
// just below and above it, each slab distance is computed from the bracket end that makes
// it nearer (entry) or farther (exit), and the entry and exit are widened by a relative
// margin larger than a float's rounding error on the three operations (kFloatMargin). The
// result is a superset of what the double test keeps. A ray whose numbers a float cannot
// bracket (coordinates beyond 1e30, a direction component whose inverse overflows a float,
// anything not finite) is marked unusable, and the double test decides for it.
class WideRay {
  public:
    inline WideRay(const Ray& ray, double t_min);

    bool usable() const { return usable_; }
    // The lanes (bit i for child i) whose boxes the ray may enter within [t_min, t_max],
    // and, per lane, a distance at or before which it enters. Lanes is how many are tested
    // at once: 1 (scalar code), 4 (a vector of four floats, SSE or NEON) or 8 (one of eight,
    // AVX); each does the same operations on every lane and keeps the same lanes. Avx2
    // only where the caller is compiled for AVX2 (see sign_bits).
    // Inlined into traversal always: there the ray's numbers stay in registers.
    template <int Lanes, bool Avx2 = false>
    [[gnu::always_inline]] inline unsigned enters(const WideNode& node, double t_max,
                                                  float t_enter[WideNode::kWidth]) const;

  private:
    // Relative widening of the float entry and exit distances: 2^-20, about 16 float
    // roundings, well over the three of a slab distance, the one of t_min or t_max and the
    // one of the widening itself.
    static constexpr float kFloatMargin = 0x1p-20f;
    // Added to the exit so that distances flushed to zero or to subnormals are not misjudged.
    static constexpr float kFloatFloor = 1e-35f;

    float near_origin_[3];  // the origin bracket's end used with the entry bound, per axis
    float far_origin_[3];   // and with the exit bound
    float inverse_[3];
    int near_bound_[3];  // which of the six box rows is the entry bound per axis (k or 3 + k)
    int far_bound_[3];
    float t_min_;
    bool usable_ = false;
};

// Calls leaf(first, count), telling it, where it takes a third argument, whether the walk
// calling it is compiled for AVX2 (as std::bool_constant), so that a leaf's own vector code
// inlined there can use that too (sign_bits), and where it takes a fourth, the ray as the
// walk prepared it for the float box test (nullptr where the walk tests boxes in double), so
// that a primitive with a hierarchy of its own can walk that with it rather than prepare it
// again.
template <bool Avx2, class Leaf>
[[gnu::always_inline]] inline decltype(auto) visit_leaf(Leaf& leaf, std::uint32_t first,
                                                        std::uint32_t count,
                                                        const WideRay* prepared) {
    if constexpr (std::is_invocable_v<Leaf&, std::uint32_t, std::uint32_t, std::bool_constant<Avx2>,
                                      const WideRay*>)
        return leaf(first, count, std::bool_constant<Avx2>{}, prepared);
    else if constexpr (std::is_invocable_v<Leaf&, std::uint32_t, std::uint32_t,
                                           std::bool_constant<Avx2>>)
        return leaf(first, count, std::bool_constant<Avx2>{});
    else
        return leaf(first, count);
}

class Bvh {
  public:
    // The most primitives a leaf holds; a leaf's count must fit its 16 bits (and the wide
    // node's 8).
    static constexpr std::size_t kMaxLeafSize = 8;
    // Deeper than this, nodes split at the median of their primitives, so traversal's
    // fixed stack can never overflow (see kStackSize).
    static constexpr int kMaxSahDepth = 48;
    // The SAH's cost of visiting a node, relative to testing one primitive. Over primitives
    // tested inline from packed leaves (a mesh's triangles) a test is cheap beside a node;
    // over a scene's objects (a call through the table and a primitive's whole test, a
    // cylinder's or a polygon's) it costs about what a node does, and smaller leaves pay:
    // lattice-30's render took 0.84 of the time with 1 instead of 2 (docs/performance.md,
    // "The SAH's node cost").
    static constexpr double kPackedNodeCost = 2.0;
    static constexpr double kObjectNodeCost = 1.0;
    // The node cost of a scene's hierarchy with `called` objects tested through the table:
    // where there are none (every object a sphere, tested inline from the leaves as a mesh's
    // triangles are) it is built as a mesh is, which renders as fast and builds faster
    // (spheres-1m 0.77 -> 0.68 s on one thread); otherwise with the object cost.
    static constexpr double node_cost(std::size_t called) {
        return called == 0 ? kPackedNodeCost : kObjectNodeCost;
    }

    // How traversal tests a wide node's boxes: in float with vector code (the default: eight
    // lanes at once where the processor has AVX2, four elsewhere), with four or eight lanes
    // at once on any processor, in float lane by lane, or in double (what a ray unusable in
    // float always gets). All offer every primitive whose box the ray crosses.
    enum class BoxTest { simd, four, eight, scalar, exact };

    // Where a build finds primitive i's box: a function and what it needs.
    struct BoundsSource {
        const void* context;
        Bounds (*bounds)(const void* context, std::uint32_t i);
    };

    // The binary nodes, and the primitives' leaf order: arrays filled on several threads,
    // so allocated without being written first (parallel.h).
    using Nodes = std::vector<BvhNode, UninitializedAllocator<BvhNode>>;
    using Order = std::vector<std::uint32_t, UninitializedAllocator<std::uint32_t>>;

    Bvh() = default;
    // Builds over the given boxes, which must be finite, with binned SAH splits, on up to
    // `threads` threads (the result is the same for any number). Primitive i is the one with
    // boxes[i]; order() lists them as the leaves hold them.
    explicit Bvh(std::span<const Bounds> boxes, int threads = 1)
        : Bvh(boxes.size(),
              {&boxes,
               [](const void* context, std::uint32_t i) {
                   return (*static_cast<const std::span<const Bounds>*>(context))[i];
               }},
              threads) {}
    // The same over `count` primitives whose boxes the source gives (each asked once, from
    // any of the threads). `node_cost` is what the SAH takes visiting a node to cost,
    // relative to testing one primitive: the higher, the larger the leaves.
    Bvh(std::size_t count, BoundsSource source, int threads = 1,
        double node_cost = kPackedNodeCost);

    // The binary tree the build made, and the wide tree traversal walks.
    std::span<const BvhNode> nodes() const { return nodes_; }
    std::span<const WideNode> wide_nodes() const { return wide_; }
    std::span<const std::uint32_t> order() const { return order_; }
    // Boxes that together hold every primitive: a cut across the wide tree, as deep as it
    // goes while there are at most `at_most` of them (at least the root's children; none
    // for an empty tree). The boxes are the nodes' own, rounded outward and padded, so a
    // ray the walk would take to a primitive crosses one of them.
    std::vector<Bounds> outline(std::size_t at_most) const;
    // Frees the binary tree, which traversal does not use (only tests inspect it).
    void drop_binary_nodes() { nodes_ = {}; }
    // Gives up the leaf order, for an owner that stores its primitives in that order itself.
    Order take_order() { return std::move(order_); }

    // Calls visit(position) for each primitive (its place in leaf order) whose leaf the ray
    // may reach in [t_min, t_max], nearer leaves first. visit may lower t_max, the best hit
    // so far, which prunes the rest; a leaf entered exactly at t_max is still visited, so
    // the caller can break ties.
    template <BoxTest Test = BoxTest::simd, class Visit>
    void closest(const Ray& ray, double t_min, double& t_max, Visit&& visit) const;
    // Calls visit(position) for candidates in [t_min, t_max] until one returns true; returns
    // whether one did.
    template <BoxTest Test = BoxTest::simd, class Visit>
    bool any(const Ray& ray, double t_min, double t_max, Visit&& visit) const;
    // As closest and any, a leaf at a time: leaf(first, count) for the primitives at
    // [first, first + count) in leaf order; for any, leaf returns true to stop. A leaf may
    // take two more arguments (visit_leaf). `prepared`, where given, must be
    // WideRay(ray, t_min) and usable: the walk then copies it rather than prepare the ray
    // again (a mesh's walk under the object hierarchy's, which prepared the same ray).
    // (Prepared: const WideRay*, or std::nullptr_t where the caller has none, so that the walk
    // is compiled without the choice.)
    template <BoxTest Test = BoxTest::simd, class Leaf, class Prepared = std::nullptr_t>
    void closest_leaves(const Ray& ray, double t_min, double& t_max, Leaf&& leaf,
                        Prepared prepared = nullptr) const {
        walk<Test, true>(
            ray, t_min, t_max,
            [&](std::uint32_t first, std::uint32_t count, auto avx2, const WideRay* walked)
                __attribute__((always_inline)) {
                    visit_leaf<decltype(avx2)::value>(leaf, first, count, walked);
                    return false;
                },
            prepared);
    }
    template <BoxTest Test = BoxTest::simd, class Leaf, class Prepared = std::nullptr_t>
    bool any_leaves(const Ray& ray, double t_min, double t_max, Leaf&& leaf,
                    Prepared prepared = nullptr) const {
        return walk<Test, false>(ray, t_min, t_max, leaf, prepared);
    }

  private:
    // With at most kMaxSahDepth SAH levels and median splits below them, no path is longer
    // than kMaxSahDepth + 32 nodes for fewer than 2^32 primitives, and no wide path longer
    // than that. Each wide node visited pushes at most eight children and pops one, so the
    // stack holds at most seven entries per level and eight more.
    static constexpr int kStackSize =
        (WideNode::kWidth - 1) * (kMaxSahDepth + 40) + WideNode::kWidth;

    void collapse(int threads);
    int wide_children(std::uint32_t binary, std::uint32_t (&children)[WideNode::kWidth]) const;
    WideNode wide_node(const std::uint32_t (&children)[WideNode::kWidth], int size) const;
    std::size_t wide_count_below(std::uint32_t binary) const;
    std::uint32_t collapse_into(std::uint32_t binary, std::uint32_t index);

    // Nearest: children entered are taken nearest first (for closest); otherwise in any order
    // (for any, which stops at the first blocker wherever it lies).
    template <BoxTest Test, bool Nearest, class Leaf, class Prepared = std::nullptr_t>
    bool walk(const Ray& ray, double t_min, const double& t_max, Leaf&& leaf,
              Prepared prepared = nullptr) const;
    // A tree that is one node of at most this many children is tested in double, without
    // the stack (see walk). With more, the float test and the nearest-first order pay
    // (mirror-49, 49 spheres in one node of eight leaves: 1.06 of the time in double).
    static constexpr int kDoubleTestedRoot = 4;
    // The walk below the root's special case, with the box test Test (not simd). Inlined
    // into walk, and into walk_avx2 where it is compiled for AVX2 (and told so by Avx2).
    template <BoxTest Test, bool Nearest, bool Avx2 = false, class Leaf, class Prepared>
    [[gnu::always_inline]] inline bool walk_nodes(const Ray& ray, double t_min, const double& t_max,
                                                  Leaf&& leaf, Prepared prepared) const;
#if RT_AVX2_PATH
    // The walk with eight lanes at once, compiled for AVX2 (taken only where the processor
    // has it): one instruction per operation on all eight, where the portable code needs two.
    template <bool Nearest, class Leaf, class Prepared>
    [[gnu::target("avx2")]] bool walk_avx2(const Ray& ray, double t_min, const double& t_max,
                                           Leaf&& leaf, Prepared prepared) const {
        return walk_nodes<BoxTest::eight, Nearest, true>(ray, t_min, t_max, leaf, prepared);
    }
#endif

    Nodes nodes_;
    // Allocated without being written first (WideNode is trivial): see collapse().
    std::vector<WideNode, UninitializedAllocator<WideNode>> wide_;
    Order order_;
};

// Nodes are visited depth first. At a wide node all children's boxes are tested at once; a lone
// child entered is taken at once; of several, for Nearest the nearest is taken at once and
// the others go on a small fixed stack with their entry distances, the farthest first (for
// any, in lane order, the last taken at once as the pop would take it), and wait; a waiting
// child is dropped without another test once a hit nearer than its entry has been found.
// leaf(first, count) returns true to stop; walk returns whether one did.
template <Bvh::BoxTest Test, bool Nearest, class Leaf, class Prepared>
bool Bvh::walk(const Ray& ray, double t_min, const double& t_max, Leaf&& leaf,
               Prepared prepared) const {
    if (wide_.empty()) return false;
    // A tree of one node of a few children (a scene of a few objects, or one mesh) takes the
    // double test: for a single node, preparing the ray for the float test costs more than
    // it saves. Its children are leaves, visited in lane order without the stack: with four
    // at most, the order's pruning is worth less than sorting them (a scene that is one mesh
    // and a plane spent a quarter of its instructions above the mesh's own walk).
    if (wide_.size() == 1 && wide_[0].size <= kDoubleTestedRoot) {
        const WideNode& node = wide_[0];
        const BoxRay box_ray(ray);
        for (int i = 0; i < node.size; ++i) {
            double t_enter = 0;
            if (box_ray.enters(node.bound(i).data(), t_min, t_max, t_enter) &&
                visit_leaf<false>(leaf, node.child[i], node.count[i], nullptr))
                return true;
        }
        return false;
    }
    if constexpr (Test == BoxTest::simd || Test == BoxTest::eight) {
#if RT_AVX2_PATH
        if (kHasAvx2) return walk_avx2<Nearest>(ray, t_min, t_max, leaf, prepared);
#endif
    }
    constexpr BoxTest kTest = Test == BoxTest::simd ? BoxTest::four : Test;
    return walk_nodes<kTest, Nearest>(ray, t_min, t_max, leaf, prepared);
}

template <Bvh::BoxTest Test, bool Nearest, bool Avx2, class Leaf, class Prepared>
bool Bvh::walk_nodes(const Ray& ray, double t_min, const double& t_max, Leaf&& leaf,
                     Prepared prepared) const {
    static_assert(std::is_same_v<Prepared, std::nullptr_t> ||
                  std::is_same_v<Prepared, const WideRay*>);
    bool exact = Test == BoxTest::exact;
    std::optional<WideRay> wide_ray;
    if (!exact) {
        // A copy: a local the leaves' calls cannot be taken to change stays in registers.
        if constexpr (std::is_same_v<Prepared, const WideRay*>) {
            if (prepared != nullptr)
                wide_ray.emplace(*prepared);
            else
                wide_ray.emplace(ray, t_min);
        } else {
            wide_ray.emplace(ray, t_min);
        }
        exact = !wide_ray->usable();
    }
    const WideRay* const walked = exact ? nullptr : &*wide_ray;
    std::optional<BoxRay> box_ray;  // only for the double test
    if (exact) box_ray.emplace(ray);
    struct Pending {
        std::uint32_t child;
        std::uint32_t count;  // 0 for a wide node
        float t_enter;
    };
    Pending stack[kStackSize];
    int top = 0;
    std::uint32_t current = 0;
    for (;;) {
        const WideNode& node = wide_[current];
        float t_enter[WideNode::kWidth];
        unsigned lanes = 0;
        if (exact) {
            for (int i = 0; i < node.size; ++i) {
                double t = 0;
                if (!box_ray->enters(node.bound(i).data(), t_min, t_max, t)) continue;
                lanes |= 1u << i;
                // Rounded down, so that the pruning below never drops what the test kept.
                const auto f = static_cast<float>(std::clamp(t, -3e38, 3e38));
                t_enter[i] = static_cast<double>(f) > t ? std::nextafter(f, -HUGE_VALF) : f;
            }
        } else {
            constexpr int kLanes = Test == BoxTest::eight ? 8 : Test == BoxTest::four ? 4 : 1;
            lanes = wide_ray->enters<kLanes, Avx2>(node, t_max, t_enter);
        }
        if (lanes != 0 && (lanes & (lanes - 1)) == 0) {
            // One child entered (the common case deep in the tree): straight into it.
            const int i = std::countr_zero(lanes);
            if (node.count[i] == 0) {
                current = node.child[i];
                continue;
            }
            if (visit_leaf<Avx2>(leaf, node.child[i], node.count[i], walked)) return true;
        } else if (lanes != 0 && Nearest) {
            // Push the children entered but the nearest, farthest first (insertion by entry
            // distance), and go on into the nearest at once: it would be popped next.
            const int base = top;
            int nearest = std::countr_zero(lanes);
            for (lanes &= lanes - 1; lanes != 0; lanes &= lanes - 1) {
                int i = std::countr_zero(lanes);
                if (t_enter[i] < t_enter[nearest]) std::swap(i, nearest);
                const Pending p{node.child[i], node.count[i], t_enter[i]};
                int at = top++;
                while (at > base && stack[at - 1].t_enter < p.t_enter) {
                    stack[at] = stack[at - 1];
                    --at;
                }
                stack[at] = p;
            }
            if (node.count[nearest] == 0) {
                current = node.child[nearest];
                continue;
            }
            if (visit_leaf<Avx2>(leaf, node.child[nearest], node.count[nearest], walked))
                return true;
        } else if (lanes != 0) {
            // In any order: the children entered are pushed in lane order but the last,
            // which would be popped next, and that one is taken at once (t_max does not
            // fall in this walk, so its check is the one the pop would make).
            const int last = 31 - std::countl_zero(lanes);
            for (lanes &= ~(1u << last); lanes != 0; lanes &= lanes - 1) {
                const int i = std::countr_zero(lanes);
                stack[top++] = {node.child[i], node.count[i], t_enter[i]};
            }
            if (t_enter[last] <= t_max) {
                if (node.count[last] == 0) {
                    current = node.child[last];
                    continue;
                }
                if (visit_leaf<Avx2>(leaf, node.child[last], node.count[last], walked)) return true;
            }
        }
        // Pop until a wide node the ray enters before the best hit so far (t_max may have
        // fallen since it was pushed), visiting leaves on the way.
        for (;;) {
            if (top == 0) return false;
            const Pending next = stack[--top];
            if (!(next.t_enter <= t_max)) continue;
            if (next.count == 0) {
                current = next.child;
                break;
            }
            if (visit_leaf<Avx2>(leaf, next.child, next.count, walked)) return true;
        }
    }
}

template <Bvh::BoxTest Test, class Visit>
void Bvh::closest(const Ray& ray, double t_min, double& t_max, Visit&& visit) const {
    walk<Test, true>(
        ray, t_min,
        t_max, [&](std::uint32_t first, std::uint32_t count) __attribute__((always_inline)) {
            for (std::uint32_t i = first, end = first + count; i < end; ++i) visit(i);
            return false;
        });
}

template <Bvh::BoxTest Test, class Visit>
bool Bvh::any(const Ray& ray, double t_min, double t_max, Visit&& visit) const {
    return walk<Test, false>(
        ray, t_min,
        t_max, [&](std::uint32_t first, std::uint32_t count) __attribute__((always_inline)) {
            for (std::uint32_t i = first, end = first + count; i < end; ++i)
                if (visit(i)) return true;
            return false;
        });
}

// Inline and without branches: a ray is prepared once per query, and for a small scene that
// is a good part of the query's work.
inline WideRay::WideRay(const Ray& ray, double t_min) {
    // Beyond these, brackets and inverses no longer fit a float with room to spare.
    constexpr double kLargest = 1e30;
    bool usable = std::fabs(t_min) <= kLargest;
    for (int k = 0; k < 3; ++k) {
        const double d = ray.direction[k];
        const double o = std::clamp(ray.origin[k], -kLargest, kLargest);
        const double inverse = 1 / d;  // +-inf for a zero component, as in BoxRay
        usable &= std::fabs(ray.origin[k]) <= kLargest && std::fabs(d) <= DBL_MAX &&
                  (std::fabs(inverse) <= kLargest || d == 0);
        // The origin's bracket: moved out by a float's relative precision and by more than
        // the smallest normal float, then rounded to the nearest float, o lands past o.
        const double room = std::fabs(o) * 0x1p-23 + 0x1p-125;
        const auto below = static_cast<float>(o - room), above = static_cast<float>(o + room);
        const bool negative = std::signbit(inverse);
        // Along a positive direction the entry is at the min bound, and the entry distance
        // (bound - origin) * inverse is smallest with the origin's upper bracket; the exit,
        // at the max bound, is largest with the lower one. A negative direction swaps both.
        near_bound_[k] = negative ? 3 + k : k;
        far_bound_[k] = negative ? k : 3 + k;
        near_origin_[k] = negative ? below : above;
        far_origin_[k] = negative ? above : below;
        // Out of range only where unusable; converted as infinite there, never overflowing.
        inverse_[k] = static_cast<float>(
            std::fabs(inverse) <= kLargest ? inverse : std::copysign(kInfinity, inverse));
    }
    usable_ = usable;
    // Rounded to the nearest float: the widening of the entry covers that rounding.
    t_min_ = static_cast<float>(std::clamp(t_min, -kLargest, kLargest));
}

// The slab test of a node's lanes, Lanes at a time. Per axis, the entry bound's row minus the
// origin, times the inverse direction, and likewise the exit; the entry is the largest of
// t_min and the three, the exit the smallest of t_max and the three. A NaN (0 * inf: a ray
// parallel to a slab with its origin on the slab's plane) loses every comparison, so that
// slab is ignored, which only keeps more. Unused lanes are masked off.
template <int Lanes, bool Avx2>
inline unsigned WideRay::enters(const WideNode& node, double t_max,
                                float t_enter[WideNode::kWidth]) const {
    static_assert(Lanes == 1 || Lanes == 4 || Lanes == 8);
    // Rounded to the nearest float: the widening below covers that rounding too.
    const float t_max_f = t_max < 3e38 ? static_cast<float>(std::max(t_max, -3e38)) : HUGE_VALF;
    constexpr float grow = 1 + kFloatMargin, shrink = 1 - kFloatMargin;
    if constexpr (Lanes > 1) {
        // Four lanes are one SSE or NEON register on every machine rt is built for; eight
        // are one AVX register, and elsewhere are split into halves by the compiler.
        using Floats = typename LaneVectors<Lanes>::Floats;
        unsigned lanes = 0;
        for (int first = 0; first < WideNode::kWidth; first += Lanes) {
            Floats near = Floats{} + t_min_, far = Floats{} + t_max_f;
            for (int k = 0; k < 3; ++k) {
                Floats near_row, far_row;
                std::memcpy(&near_row, node.box[near_bound_[k]] + first, sizeof near_row);
                std::memcpy(&far_row, node.box[far_bound_[k]] + first, sizeof far_row);
                const Floats slab_near = (near_row - near_origin_[k]) * inverse_[k];
                const Floats slab_far = (far_row - far_origin_[k]) * inverse_[k];
                near = slab_near > near ? slab_near : near;
                far = slab_far < far ? slab_far : far;
            }
            near = near * (near >= 0 ? Floats{} + shrink : Floats{} + grow);
            far = far * (far >= 0 ? Floats{} + grow : Floats{} + shrink) + kFloatFloor;
            // The comparison gives all ones (a set sign bit) where a lane is in.
            std::memcpy(t_enter + first, &near, sizeof near);
            lanes |= sign_bits<Lanes, Avx2>(near <= far) << first;
        }
        return lanes & ((1u << node.size) - 1);
    } else {
        unsigned lanes = 0;
        for (int i = 0; i < node.size; ++i) {
            float near = t_min_, far = t_max_f;
            for (int k = 0; k < 3; ++k) {
                const float slab_near =
                    (node.box[near_bound_[k]][i] - near_origin_[k]) * inverse_[k];
                const float slab_far = (node.box[far_bound_[k]][i] - far_origin_[k]) * inverse_[k];
                near = slab_near > near ? slab_near : near;
                far = slab_far < far ? slab_far : far;
            }
            near = near * (near >= 0 ? shrink : grow);
            far = far * (far >= 0 ? grow : shrink) + kFloatFloor;
            t_enter[i] = near;
            if (near <= far) lanes |= 1u << i;
        }
        return lanes;
    }
}

}  // namespace rt
