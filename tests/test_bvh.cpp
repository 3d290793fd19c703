// The bounding volume hierarchy: its structure on random boxes, and the promise that it
// changes nothing. The linear scan (--no-bvh) is the oracle: on seeded random scenes of every
// primitive type, overlapping, coincident and nested in affines, both must find the same
// object at the same distance for every ray and render the same image on any thread count.
#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "accel/bvh.h"
#include "accel/object_index.h"
#include "accel/parallel.h"
#include "memory_checks.h"  // RT_MEASURES_MEMORY: 0 under ASan
#include "rt/large_pages.h"
#include "rt/render.h"
#include "rt/trace.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

Bounds node_box(const BvhNode& n) {
    const auto& b = n.bound;
    return {{b[0], b[1], b[2]}, {b[3], b[4], b[5]}};
}

bool box_holds(const Bounds& outer, const Bounds& inner) {
    return outer.contains(inner.min) && outer.contains(inner.max);
}

// Checks the tree below `index`: boxes nest, leaves are small, every path is bounded.
// Returns the number of primitives below.
std::size_t check_subtree(const Bvh& bvh, std::span<const Bounds> boxes, std::uint32_t index,
                          int depth, int& deepest) {
    const BvhNode& node = bvh.nodes()[index];
    deepest = std::max(deepest, depth);
    const Bounds box = node_box(node);
    if (node.is_leaf()) {
        CHECK(node.count <= Bvh::kMaxLeafSize);
        for (std::uint32_t i = node.offset; i < node.offset + node.count; ++i)
            CHECK(box_holds(box, boxes[bvh.order()[i]]));
        return node.count;
    }
    const std::uint32_t first = index + 1, second = node.offset;
    CHECK(second > first && second < bvh.nodes().size());
    CHECK(box_holds(box, node_box(bvh.nodes()[first])));
    CHECK(box_holds(box, node_box(bvh.nodes()[second])));
    return check_subtree(bvh, boxes, first, depth + 1, deepest) +
           check_subtree(bvh, boxes, second, depth + 1, deepest);
}

// A box's centre as the build computes it (halves first, then rounded to a float).
float build_centre(const Bounds& b, int axis) {
    return static_cast<float>(b.min[axis] * 0.5 + b.max[axis] * 0.5);
}

// The leaf-order places [first, end) below `index`, after checking that an interior node's
// two children are a split by position: their places are adjacent, and along some axis no
// centre of the first child lies beyond any of the second's. A reference the partition left
// on the wrong side would break that.
std::pair<std::uint32_t, std::uint32_t> check_split(const Bvh& bvh, std::span<const Bounds> boxes,
                                                    std::uint32_t index) {
    const BvhNode& node = bvh.nodes()[index];
    if (node.is_leaf()) return {node.offset, node.offset + node.count};
    const auto first = check_split(bvh, boxes, index + 1);
    const auto second = check_split(bvh, boxes, node.offset);
    CHECK_EQ(first.second, second.first);
    bool separated = false;
    for (int axis = 0; axis < 3 && !separated; ++axis) {
        float first_max = -HUGE_VALF, second_min = HUGE_VALF;
        for (std::uint32_t i = first.first; i < first.second; ++i)
            first_max = std::max(first_max, build_centre(boxes[bvh.order()[i]], axis));
        for (std::uint32_t i = second.first; i < second.second; ++i)
            second_min = std::min(second_min, build_centre(boxes[bvh.order()[i]], axis));
        separated = first_max <= second_min;
    }
    CHECK(separated);
    return {first.first, second.second};
}

void check_structure(std::span<const Bounds> boxes) {
    const Bvh bvh(boxes);
    const auto whole = check_split(bvh, boxes, 0);
    CHECK(whole.first == 0 && whole.second == boxes.size());
    // Every primitive appears in the leaves exactly once.
    std::vector<std::uint32_t> order(bvh.order().begin(), bvh.order().end());
    std::sort(order.begin(), order.end());
    bool permutation = order.size() == boxes.size();
    for (std::uint32_t i = 0; permutation && i < order.size(); ++i) permutation = order[i] == i;
    CHECK(permutation);
    int deepest = 0;
    CHECK_EQ(check_subtree(bvh, boxes, 0, 0, deepest), boxes.size());
    CHECK(deepest <= Bvh::kMaxSahDepth + 32);
}

std::vector<Bounds> random_boxes(Random& random, std::size_t count, double spread, double size) {
    std::vector<Bounds> boxes;
    for (std::size_t i = 0; i < count; ++i) {
        const Vec3 c = random.in_box(spread);
        const Vec3 h{random.uniform(0, size), random.uniform(0, size), random.uniform(0, size)};
        boxes.push_back({c - h, c + h});
    }
    return boxes;
}

// Whether the ray passes through the box's inside, well away from its edges (so that no
// rounding can decide it): then the hierarchy must offer that primitive.
bool clearly_crosses(const Ray& ray, const Bounds& b) {
    double near = 0, far = kInfinity;
    for (int k = 0; k < 3; ++k) {
        const double lo = (b.min[k] - ray.origin[k]) / ray.direction[k];
        const double hi = (b.max[k] - ray.origin[k]) / ray.direction[k];
        near = std::max(near, std::min(lo, hi));
        far = std::min(far, std::max(lo, hi));
    }
    return near + 1e-6 < far;
}

}  // namespace

TEST(structure_of_random_boxes) {
    Random random(1);
    // From 128 references on, a node is partitioned in blocks of 64 on each side first.
    for (const std::size_t n : {1, 2, 3, 9, 100, 127, 128, 129, 200, 5000, 30000})
        check_structure(random_boxes(random, n, 10, 1));
}

TEST(structure_when_boxes_coincide_or_are_flat) {
    // Identical boxes give no split by position: the build splits evenly instead.
    check_structure(std::vector<Bounds>(3000, Bounds{{0, 0, 0}, {1, 1, 1}}));
    // Flat boxes (triangles in axis planes) and points.
    std::vector<Bounds> flat;
    Random random(2);
    for (int i = 0; i < 2000; ++i) {
        const Vec3 p = random.in_box(5);
        flat.push_back({p, {p.x + 1, p.y, p.z + (i % 3 == 0 ? 0 : 1)}});
        flat.push_back({p, p});
    }
    check_structure(flat);
}

TEST(structure_with_extreme_sizes) {
    // Sizes spread over hundreds of orders of magnitude: SAH splits peel off one box at a time
    // here, so the depth limit's median splits must take over.
    std::vector<Bounds> boxes;
    for (int i = 0; i < 600; ++i) {
        const double s = std::ldexp(1.0, i - 300);
        boxes.push_back({{s, s, s}, {2 * s, 2 * s, 2 * s}});
    }
    boxes.push_back({{-1e300, -1e300, -1e300}, {1e300, 1e300, 1e300}});  // beyond float range
    check_structure(boxes);
}

TEST(a_cheaper_node_splits_the_same_leaves_further) {
    // The node cost only decides between a leaf and its best split, never which split: so
    // the tree built with the scene's cost refines the one built with a mesh's. Each of the
    // latter's leaves holds the same primitives as a run of the former's, and there are
    // more of those.
    Random random(4);
    const std::vector<Bounds> boxes = random_boxes(random, 5000, 10, 1);
    const Bvh::BoundsSource source{
        &boxes, [](const void* context, std::uint32_t i) {
            return (*static_cast<const std::vector<Bounds>*>(context))[i];
        }};
    const Bvh packed(boxes.size(), source, 1, Bvh::kPackedNodeCost);
    const Bvh objects(boxes.size(), source, 1, Bvh::kObjectNodeCost);
    auto leaf_starts = [](const Bvh& bvh) {
        std::vector<std::uint32_t> starts;
        for (const BvhNode& node : bvh.nodes())
            if (node.is_leaf()) starts.push_back(node.offset);
        std::sort(starts.begin(), starts.end());
        return starts;
    };
    const std::vector<std::uint32_t> coarse = leaf_starts(packed), fine = leaf_starts(objects);
    CHECK(fine.size() > coarse.size());
    CHECK(std::includes(fine.begin(), fine.end(), coarse.begin(), coarse.end()));
    for (std::size_t k = 0; k < coarse.size(); ++k) {
        const std::uint32_t begin = coarse[k];
        const auto end =
            static_cast<std::uint32_t>(k + 1 < coarse.size() ? coarse[k + 1] : boxes.size());
        std::vector<std::uint32_t> a(packed.order().begin() + begin, packed.order().begin() + end);
        std::vector<std::uint32_t> b(objects.order().begin() + begin,
                                     objects.order().begin() + end);
        std::sort(a.begin(), a.end());
        std::sort(b.begin(), b.end());
        if (a != b) {
            record_failure(__FILE__, __LINE__, "leaf at " + std::to_string(begin) + " differs");
            break;
        }
    }
}

double half_area(const Bounds& b) {
    const Vec3 d = b.max - b.min;
    return d.x * d.y + d.y * d.z + d.z * d.x;
}

Bounds box_of(std::span<const Bounds> boxes, std::span<const std::uint32_t> which) {
    Bounds b;
    for (const std::uint32_t i : which) {
        b.expand(boxes[i].min);
        b.expand(boxes[i].max);
    }
    return b;
}

TEST(a_small_node_takes_the_cheapest_split_of_its_sorted_centres) {
    // Nodes of up to 32 references are split by a sweep over every place between distinct
    // centres along the axis, not by bins: the root's split (or its leaf) must be the cheapest
    // of those by the SAH, within the float boxes' rounding.
    Random random(41);
    int splits = 0, leaves = 0;
    for (int trial = 0; trial < 600; ++trial) {
        const auto n = static_cast<std::size_t>(3 + trial % 30);
        std::vector<Bounds> boxes = random_boxes(random, n, 10, trial % 2 == 0 ? 1 : 40);
        if (trial % 3 == 0) boxes[1] = boxes[0];  // a pair of equal centres
        const Bvh bvh(boxes);
        double centre_lo[3], centre_hi[3];
        for (int k = 0; k < 3; ++k) {
            centre_lo[k] = HUGE_VAL;
            centre_hi[k] = -HUGE_VAL;
            for (const Bounds& b : boxes) {
                centre_lo[k] = std::min<double>(centre_lo[k], build_centre(b, k));
                centre_hi[k] = std::max<double>(centre_hi[k], build_centre(b, k));
            }
        }
        const double extent[3] = {centre_hi[0] - centre_lo[0], centre_hi[1] - centre_lo[1],
                                  centre_hi[2] - centre_lo[2]};
        const int axis = extent[0] >= extent[1] && extent[0] >= extent[2] ? 0
                         : extent[1] >= extent[2]                         ? 1
                                                                          : 2;
        std::vector<std::uint32_t> sorted(n);
        for (std::uint32_t i = 0; i < n; ++i) sorted[i] = i;
        std::sort(sorted.begin(), sorted.end(), [&](std::uint32_t a, std::uint32_t b) {
            return build_centre(boxes[a], axis) < build_centre(boxes[b], axis);
        });
        const double whole = half_area(box_of(boxes, sorted));
        double cheapest = HUGE_VAL;
        for (std::size_t s = 1; s < n; ++s) {
            if (!(build_centre(boxes[sorted[s - 1]], axis) < build_centre(boxes[sorted[s]], axis)))
                continue;
            const std::span<const std::uint32_t> all(sorted);
            const double cost =
                static_cast<double>(s) * half_area(box_of(boxes, all.first(s))) +
                static_cast<double>(n - s) * half_area(box_of(boxes, all.subspan(s)));
            cheapest = std::min(cheapest, Bvh::kPackedNodeCost + cost / whole);
        }
        const BvhNode& root = bvh.nodes()[0];
        if (root.is_leaf()) {
            ++leaves;
            CHECK(n <= Bvh::kMaxLeafSize);
            CHECK(cheapest >= static_cast<double>(n) * (1 - 1e-4));
            continue;
        }
        ++splits;
        const BvhNode& first = bvh.nodes()[1];
        const BvhNode& second = bvh.nodes()[root.offset];
        const std::uint32_t middle = check_split(bvh, boxes, 1).second;
        const double chosen =
            Bvh::kPackedNodeCost + (middle * half_area(node_box(first)) +
                                    static_cast<double>(n - middle) * half_area(node_box(second))) /
                                       half_area(node_box(root));
        CHECK(chosen <= cheapest * (1 + 1e-4));
        // Never between equal centres (the bins' rule too): apart along the axis.
        float first_max = -HUGE_VALF, second_min = HUGE_VALF;
        for (std::uint32_t i = 0; i < n; ++i) {
            const float c = build_centre(boxes[bvh.order()[i]], axis);
            if (i < middle)
                first_max = std::max(first_max, c);
            else
                second_min = std::min(second_min, c);
        }
        CHECK(first_max < second_min);
    }
    CHECK(splits > 300 && leaves > 20);
    // Centres along x a few units in the last place apart, in no order (the ranks' keys
    // cannot tell the nearest of them apart): every split still parts them by position.
    int parted = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const auto n = static_cast<std::size_t>(9 + trial % 24);
        std::vector<Bounds> boxes;
        for (std::size_t i = 0; i < n; ++i) {
            const double x = 4 + static_cast<double>(random.next() % 40) * 0x1p-21;  // float ulps
            boxes.push_back({{x - 1, -1, -1}, {x + 1, 1, 1}});
        }
        const Bvh bvh(boxes);
        for (std::uint32_t index = 0; index < bvh.nodes().size(); ++index) {
            const BvhNode& node = bvh.nodes()[index];
            if (node.is_leaf()) continue;
            const auto first = check_split(bvh, boxes, index + 1);
            const auto second = check_split(bvh, boxes, node.offset);
            float first_max = -HUGE_VALF, second_min = HUGE_VALF;
            for (std::uint32_t i = first.first; i < first.second; ++i)
                first_max = std::max(first_max, build_centre(boxes[bvh.order()[i]], 0));
            for (std::uint32_t i = second.first; i < second.second; ++i)
                second_min = std::min(second_min, build_centre(boxes[bvh.order()[i]], 0));
            CHECK(first_max < second_min);
            ++parted;
        }
    }
    CHECK(parted > 200);
}

TEST(a_scene_of_spheres_only_takes_a_meshs_node_cost) {
    // Spheres are tested inline from the leaves, as a mesh's triangles are; any object
    // tested through the table makes the scene's hierarchy take the object cost.
    CHECK_EQ(Bvh::node_cost(0), Bvh::kPackedNodeCost);
    CHECK_EQ(Bvh::node_cost(1), Bvh::kObjectNodeCost);
    CHECK(Bvh::kObjectNodeCost < Bvh::kPackedNodeCost);
}

TEST(the_same_tree_on_any_number_of_threads) {
    // Enough boxes that the build hands subtrees to helper threads two levels down (a helper
    // takes a child of at least 50,000), with some coincident centres and some flat boxes.
    Random random(5);
    std::vector<Bounds> boxes = random_boxes(random, 220000, 50, 0.5);
    for (std::size_t i = 0; i < boxes.size(); i += 97) boxes[i] = boxes[i / 2];
    for (std::size_t i = 0; i < boxes.size(); i += 89) boxes[i].max.y = boxes[i].min.y;
    const Bvh one(boxes, 1);
    // Under ASan, where every build is several times slower, one other thread count.
    const std::vector<int> counts =
        RT_MEASURES_MEMORY ? std::vector<int>{2, 3, 8} : std::vector<int>{3};
    for (const int threads : counts) {
        const Bvh many(boxes, threads);
        CHECK_EQ(many.nodes().size(), one.nodes().size());
        CHECK(std::memcmp(many.nodes().data(), one.nodes().data(),
                          one.nodes().size() * sizeof(BvhNode)) == 0);
        CHECK_EQ(many.wide_nodes().size(), one.wide_nodes().size());
        CHECK(std::memcmp(many.wide_nodes().data(), one.wide_nodes().data(),
                          one.wide_nodes().size() * sizeof(WideNode)) == 0);
        CHECK(std::equal(many.order().begin(), many.order().end(), one.order().begin(),
                         one.order().end()));
    }
    if (RT_MEASURES_MEMORY) check_structure(boxes);  // smaller sets check it under ASan too
}

TEST(parallel_parts_cover_the_range_once) {
    for (const std::size_t count : {0, 1, 999, 1000, 2500, 200003}) {
        for (const int threads : {0, 1, 2, 3, 8}) {
            std::vector<std::atomic<int>> visits(count);
            std::mutex lock;
            std::set<std::thread::id> ids;
            std::size_t parts = 0;
            parallel_parts(count, threads, 1000, [&](std::size_t begin, std::size_t end) {
                for (std::size_t i = begin; i < end; ++i) ++visits[i];
                const std::scoped_lock hold(lock);
                ids.insert(std::this_thread::get_id());
                ++parts;
            });
            CHECK(std::all_of(visits.begin(), visits.end(), [](auto& v) { return v == 1; }));
            // One part per thread at most, none shorter than the minimum (but for one).
            const std::size_t most = std::clamp<std::size_t>(count / 1000, 1, std::max(threads, 1));
            CHECK_EQ(parts, most);
            CHECK_EQ(ids.size(), parts);
        }
    }
}

TEST(parallel_parts_pass_a_failure_on) {
    bool caught = false;
    try {
        parallel_parts(10000, 4, 1000, [](std::size_t begin, std::size_t) {
            if (begin > 0) throw std::runtime_error("part failed");
        });
    } catch (const std::runtime_error& e) {
        caught = std::string(e.what()) == "part failed";
    }
    CHECK(caught);
}

TEST(large_arrays_take_whole_huge_pages_and_small_ones_their_alignment) {
    for (const std::size_t bytes : {std::size_t{1}, std::size_t{100}, kLargeArrayBytes - 1,
                                    kLargeArrayBytes, kLargeArrayBytes + 1, 3 * kLargeArrayBytes}) {
        for (const std::size_t alignment : {std::size_t{4}, std::size_t{16}, std::size_t{64}}) {
            auto* const p = static_cast<unsigned char*>(allocate_array(bytes, alignment));
            const auto address = reinterpret_cast<std::uintptr_t>(p);
            CHECK_EQ(address % alignment, 0u);
#if defined(__linux__)
            // Where huge pages can back them: an array of whole 2 MiB pages.
            if (bytes >= kLargeArrayBytes) CHECK_EQ(address % kLargeArrayBytes, 0u);
#endif
            // Every byte writable, and what is written stays.
            std::memset(p, 0xA5, bytes);
            CHECK(p[0] == 0xA5 && p[bytes / 2] == 0xA5 && p[bytes - 1] == 0xA5);
            free_array(p, bytes, alignment);
        }
    }
}

TEST(a_vector_keeps_its_elements_as_it_grows_into_huge_pages_and_back) {
    // Growing across the threshold moves the elements from operator new's memory to mapped
    // pages; shrinking to fit moves them back. Under ASan a free of the wrong kind or size fails.
    std::vector<WideNode, UninitializedAllocator<WideNode>> nodes;
    const std::size_t count = 3 * kLargeArrayBytes / sizeof(WideNode);
    for (std::size_t i = 0; i < count; ++i) {
        WideNode n{};
        n.child[0] = static_cast<std::uint32_t>(i);
        n.box[5][7] = static_cast<float>(i);
        nodes.push_back(n);
    }
    CHECK_EQ(reinterpret_cast<std::uintptr_t>(nodes.data()) % alignof(WideNode), 0u);
    bool kept = true;
    for (std::size_t i = 0; i < count; ++i)
        kept = kept && nodes[i].child[0] == i && nodes[i].box[5][7] == static_cast<float>(i);
    CHECK(kept);
    nodes.resize(10);
    nodes.shrink_to_fit();
    CHECK(nodes.size() == 10 && nodes[9].child[0] == 9);
}

TEST(traversal_offers_every_box_the_ray_crosses) {
    Random random(3);
    const std::vector<Bounds> boxes = random_boxes(random, 4000, 10, 0.7);
    const Bvh bvh(boxes);
    for (int r = 0; r < 2000; ++r) {
        const Ray ray{random.in_box(12), random.unit_vector()};
        std::vector<bool> offered(boxes.size(), false);
        double t_max = kInfinity;
        bvh.closest(ray, 0, t_max, [&](std::uint32_t i) { offered[bvh.order()[i]] = true; });
        bool all = true;
        for (std::size_t i = 0; i < boxes.size(); ++i)
            if (clearly_crosses(ray, boxes[i]) && !offered[i]) all = false;
        CHECK(all);
    }
}

TEST(traversal_with_axis_parallel_rays_on_box_faces) {
    // A ray parallel to a slab with its origin on the slab's plane: 0 * inf in the slab test.
    const std::vector<Bounds> boxes{{{0, 0, 0}, {1, 1, 1}}, {{2, 0, 0}, {3, 1, 0}}};
    const Bvh bvh(boxes);
    for (const Ray& ray : {Ray{{-1, 0, 0}, {1, 0, 0}}, Ray{{-1, 1, 0.5}, {1, 0, 0}},
                           Ray{{2.5, 0.5, -1}, {0, 0, 1}}, Ray{{0, 0, -3}, {0, 0, 1}}}) {
        std::size_t offered = 0;
        double t_max = kInfinity;
        bvh.closest(ray, 0, t_max, [&](std::uint32_t) { ++offered; });
        CHECK(offered >= 1);
    }
}

TEST(any_stops_at_the_first_yes) {
    Random random(4);
    const std::vector<Bounds> boxes = random_boxes(random, 500, 3, 1);
    const Bvh bvh(boxes);
    int calls = 0;
    CHECK(bvh.any(Ray{{-10, 0, 0}, {1, 0, 0}}, 0, kInfinity, [&](std::uint32_t) {
        ++calls;
        return true;
    }));
    CHECK_EQ(calls, 1);
    CHECK(!Bvh().any(Ray{{0, 0, 0}, {1, 0, 0}}, 0, kInfinity, [](std::uint32_t) { return true; }));
}

// ---- The oracle: the same scene with and without the hierarchy ----

namespace {

// Writes random scenes with every primitive type. Coordinates are often multiples of 1/4, so
// that faces coincide exactly, boxes are flat, and some objects are exact duplicates.
class SceneWriter {
  public:
    explicit SceneWriter(std::uint64_t seed) : random_(seed) { text_.precision(17); }

    std::string scene(int objects, int resolution) {
        text_ << "102  0 2 30  0 0 0  1 0 0  0 1 0  " << resolution << ' ' << resolution << '\n';
        text_ << "103 0.1 0.1 0.1\n104 -20 30 40  0.6 0.6 0.6\n101 15 10 20  300 300 300\n";
        text_ << "2 -11 0 1 0 " << surface() << '\n';  // a floor
        text_ << "7  0 0 -12  1 0 0  0 1 0  0.2 0 1  2 0 0 0 1 " << surface() << '\n';
        std::string previous;
        for (int i = 0; i < objects; ++i) {
            // Now and then the same object again: a tie the file order must break.
            if (random_.uniform() < 0.08) {
                composite(0);  // its operands carry their surfaces
                text_ << '\n';
                continue;
            }
            if (previous.empty() || random_.uniform() >= 0.05) previous = primitive_text();
            text_ << previous << ' ' << surface() << '\n';
        }
        return text_.str();
    }

  private:
    double coordinate(double half) {
        const double x = random_.uniform(-half, half);
        return random_.uniform() < 0.5 ? std::round(x * 4) / 4 : x;
    }
    void point(double half) {
        text_ << ' ' << coordinate(half) << ' ' << coordinate(half) << ' ' << coordinate(half);
    }
    void vec(const Vec3& v) { text_ << ' ' << v.x << ' ' << v.y << ' ' << v.z; }
    Vec3 direction() {
        if (random_.uniform() < 0.3) {  // along an axis
            Vec3 v;
            const double s = random_.uniform() < 0.5 ? -1 : 1;
            switch (random_.next() % 3) {
                case 0:
                    v = {s, 0, 0};
                    break;
                case 1:
                    v = {0, s, 0};
                    break;
                default:
                    v = {0, 0, s};
                    break;
            }
            return v;
        }
        return random_.unit_vector();
    }
    std::string surface() {
        std::ostringstream s;
        s << "100 " << random_.uniform() << ' ' << random_.uniform() << ' ' << random_.uniform();
        switch (random_.next() % 4) {
            case 0:
                s << " 0.5 20 0.5 0 1";
                break;  // a mirror
            case 1:
                s << " 0.1 10 0.3 0.7 1.5";
                break;  // glass-like
            default:
                s << " 0.2 30 0.8 0 1";
                break;  // diffuse
        }
        return s.str();
    }

    // One primitive's text, written apart from the scene so that it can be repeated.
    std::string primitive_text() {
        std::ostringstream one;
        one.precision(17);
        std::swap(one, text_);
        primitive(0);
        std::swap(one, text_);
        return one.str();
    }

    // A union, intersection or difference of two solids (nested now and then), each
    // operand with its own surface.
    void composite(int nesting) {
        text_ << 20 + random_.next() % 3;
        for (int operand = 0; operand < 2; ++operand) {
            text_ << "  ";
            if (nesting < 2 && random_.uniform() < 0.25) {
                composite(nesting + 1);
                continue;
            }
            if (random_.uniform() < 0.25) {
                affine_frame();
                text_ << ' ';
            }
            // A sphere, a torus, a box or a clipped quadric (whose solid is not clipped).
            constexpr std::uint64_t kSolids[] = {0, 7, 9, 12};
            primitive_of_kind(kSolids[random_.next() % 4], nesting);
            text_ << ' ' << surface();
        }
    }

    void affine_frame() {
        text_ << "7";
        point(10);
        const Frame f = frame_around(random_.unit_vector());
        vec(f.e1 * random_.uniform(0.5, 1.5));
        vec(f.e2 * random_.uniform(0.5, 1.5) + f.e1 * random_.uniform(-0.3, 0.3));
        vec(f.e3 * random_.uniform(0.5, 1.5));
    }

    // One primitive (ID and numbers, no surface) around a random place.
    void primitive(int nesting) {
        const int kinds = nesting < 2 ? 14 : 13;
        primitive_of_kind(random_.next() % static_cast<std::uint64_t>(kinds), nesting);
    }

    void primitive_of_kind(std::uint64_t kind, int nesting) {
        const double h = 10;  // objects lie in [-h, h]^3
        switch (kind) {
            case 0:
                text_ << "1 " << random_.uniform(0.2, 1.5);
                point(h);
                break;
            case 1:
                text_ << "3";
                point(h);
                vec(direction());
                text_ << ' ' << random_.uniform(0.2, 1.5);
                break;
            case 2: {
                const double outer = random_.uniform(0.4, 1.5);
                text_ << "4";
                point(h);
                vec(direction());
                text_ << ' ' << outer << ' ' << outer * random_.uniform(0, 0.9);
                break;
            }
            case 3: {  // often in a plane z = const, with edges on the 1/4 grid
                const Vec3 c{coordinate(h), coordinate(h), coordinate(h)};
                const bool flat = random_.uniform() < 0.4;
                auto edge = [&] {
                    return Vec3(coordinate(1), coordinate(1), flat ? 0 : coordinate(1));
                };
                Vec3 a = edge();
                if (length(a) < 0.2) a = {0.5, 0, 0.25};
                Vec3 b = edge();
                if (length(cross(a, b)) < 0.05) b = cross(a, {0, 0, 1}) + Vec3(0.25, 0.5, 0);
                if (length(cross(a, b)) < 0.05) b = {0.5, 0.25, 0};
                text_ << "5";
                vec(c);
                vec(c + a);
                vec(c + b);
                break;
            }
            case 4:
                text_ << "6";
                point(h);
                vec(Vec3(0.25 + std::fabs(coordinate(1.5)), 0, 0));
                vec(Vec3(0, 0.25 + std::fabs(coordinate(1.5)), coordinate(1.5)));
                break;
            case 5:
                text_ << "8 " << random_.uniform(0.5, 0.95) << " 0 " << random_.uniform(0.3, 1.5);
                point(h);
                vec(direction());
                break;
            case 6:
                text_ << "9 " << random_.uniform(0.2, 1) << ' ' << random_.uniform(-1, 0) << ' '
                      << random_.uniform(0.1, 2);
                point(h);
                vec(direction());
                break;
            case 7: {
                const double major = random_.uniform(0.4, 1.5);
                text_ << "10";
                point(h);
                vec(direction());
                text_ << ' ' << major << ' ' << major * random_.uniform(0.1, 0.6);
                break;
            }
            case 8: {  // a regular polygon in a random plane
                const int n = 3 + static_cast<int>(random_.next() % 6);
                const Frame f = frame_around(direction());
                const Vec3 c{coordinate(h), coordinate(h), coordinate(h)};
                const double r = random_.uniform(0.3, 1.5);
                text_ << "11 " << n;
                for (int v = 0; v < n; ++v) {
                    const double a = 2 * 3.141592653589793 * v / n;
                    vec(c + r * (std::cos(a) * f.e1 + std::sin(a) * f.e2));
                }
                break;
            }
            case 9: {
                text_ << "12";
                const Vec3 lo{coordinate(h), coordinate(h), coordinate(h)};
                vec(lo);
                vec(lo + Vec3(random_.uniform(0.1, 2), random_.uniform(0.1, 2),
                              random_.uniform(0.1, 2)));
                break;
            }
            case 10:
                text_ << "1 " << random_.uniform(0.05, 0.4);
                point(h);
                break;
            case 11: {  // a small mesh: a fan of triangles around a shared vertex
                const int n = 3 + static_cast<int>(random_.next() % 8);
                const Frame f = frame_around(direction());
                const Vec3 c{coordinate(h), coordinate(h), coordinate(h)};
                text_ << "14 " << n + 1 << ' ' << n;
                vec(c);
                for (int v = 0; v < n; ++v) {
                    const double a = 2 * 3.141592653589793 * v / n;
                    vec(c + random_.uniform(0.3, 1.5) * (std::cos(a) * f.e1 + std::sin(a) * f.e2) +
                        random_.uniform(-0.5, 0.5) * f.e3);
                }
                for (int v = 0; v < n; ++v) text_ << " 0 " << v + 1 << ' ' << (v + 1) % n + 1;
                break;
            }
            case 12: {  // a quadric about c: an ellipsoid, a hyperboloid or a saddle, clipped
                const Vec3 c{coordinate(h), coordinate(h), coordinate(h)};
                const double a = random_.uniform(0.5, 2);
                const double b = random_.uniform(0.5, 2) * (random_.uniform() < 0.5 ? 1 : -1);
                const double e = random_.uniform(0.5, 2) * (random_.uniform() < 0.5 ? 1 : -1);
                const double d = random_.uniform(-0.2, 0.2), f = random_.uniform(-0.2, 0.2),
                             g = random_.uniform(-0.2, 0.2);
                // Q = [a d f; d b g; f g e]; the linear part -Qc puts the centre at c.
                const Vec3 qc{a * c.x + d * c.y + f * c.z, d * c.x + b * c.y + g * c.z,
                              f * c.x + g * c.y + e * c.z};
                text_ << "13 " << a << ' ' << b << ' ' << e << ' ' << d << ' ' << f << ' ' << g;
                vec(-qc);
                text_ << ' ' << dot(c, qc) - random_.uniform(0.2, 1);
                vec(c - Vec3(random_.uniform(0.3, 1.5), random_.uniform(0.3, 1.5),
                             random_.uniform(0.3, 1.5)));
                vec(c + Vec3(random_.uniform(0.3, 1.5), random_.uniform(0.3, 1.5),
                             random_.uniform(0.3, 1.5)));
                break;
            }
            default: {  // an affine around any of the above, or around another affine
                affine_frame();
                text_ << ' ';
                primitive(nesting + 1);
                break;
            }
        }
    }
    Random random_;
    std::ostringstream text_;
};

RenderOptions linear_options() {
    RenderOptions o;
    o.accelerate = false;
    return o;
}

bool same_bits(double a, double b) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

bool same_image(const Raster& a, const Raster& b) {
    if (a.width() != b.width() || a.height() != b.height()) return false;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            for (std::size_t i = 0; i < kSpectrumComponents; ++i)
                if (!same_bits(a.at(x, y)[i], b.at(x, y)[i])) return false;
    return true;
}

// Counts rays on which the two tracers disagree about the nearest hit or a shadow. With
// targets, every other ray is aimed at one of them.
int disagreements(const Scene& scene, Random& random, int rays,
                  const std::vector<Vec3>& targets = {}) {
    Tracer fast(scene, {});
    Tracer slow(scene, linear_options());
    int differ = 0;
    for (int r = 0; r < rays; ++r) {
        // From outside, from inside the crowd, and along the axes (rays parallel to slabs).
        Vec3 origin = random.in_box(r % 3 == 0 ? 25 : 11);
        if (r % 5 == 0) origin = {std::round(origin.x), std::round(origin.y), std::round(origin.z)};
        Vec3 direction = random.unit_vector();
        if (r % 7 == 0) direction = {0, r % 2 == 0 ? -1.0 : 1.0, 0};
        if (!targets.empty() && r % 2 == 1) {
            const Vec3 target = targets[random.next() % targets.size()] + random.in_box(0.5);
            if (length(target - origin) > 0) direction = normalized(target - origin);
        }
        const Ray ray{origin, direction};
        const auto a = fast.closest_hit(ray);
        const auto b = slow.closest_hit(ray);
        const bool same = a.has_value() == b.has_value() &&
                          (!a || (a->object == b->object && same_bits(a->hit.t, b->hit.t) &&
                                  a->hit.part == b->hit.part));
        const double distance = random.uniform(0.1, 30);
        if (!same || fast.blocked(ray, distance) != slow.blocked(ray, distance)) {
            ++differ;
            std::cerr << "differ: ray " << show(origin) << " " << show(direction) << " d "
                      << distance << " fast " << (a ? a->object - &scene.objects[0] : -1) << " t "
                      << (a ? show(a->hit.t) : "") << " slow "
                      << (b ? b->object - &scene.objects[0] : -1) << " t "
                      << (b ? show(b->hit.t) : "") << " blocked " << fast.blocked(ray, distance)
                      << slow.blocked(ray, distance) << "\n";
        }
    }
    return differ;
}

}  // namespace

TEST(same_nearest_hit_and_shadows_as_the_linear_scan) {
    // One scene under ASan, where it is the memory that is checked, at a sixth of the speed.
    const std::uint64_t seeds = RT_MEASURES_MEMORY ? 3 : 1;
    for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
        const Scene scene = parse_scene(SceneWriter(seed).scene(3000, 8));
        CHECK(scene.index->bounded_count() > 2900);
        CHECK(scene.index->unbounded_count() == 2);  // the floor and the affine plane
        Random random(seed * 101);
        CHECK_EQ(disagreements(scene, random, 4000), 0);
    }
}

// Spheres that overlap heavily (shells on a spiral, as the bench's shells scene, each a little
// smaller than the one before, with exact duplicates and cylinders among them) fill large
// leaves, whose spheres the index culls eight at a time (SphereCull) before their exact
// tests: the nearest hits and the shadows must still be the linear scan's, to the bit, with
// half the rays aimed at centres and half of those at surfaces, where rays graze.
// Spheres on a spiral, each a little smaller than the one before, every tenth twice (a tie
// the file order must break), with a disk every fiftieth: enough overlap for the index to cull
// them (SphereCull). Their centres and points on their surfaces go into targets.
std::string spiral_of_spheres(Random& random, std::vector<Vec3>& targets) {
    std::ostringstream text;
    text.precision(17);
    const char* const surface = " 100 0.8 0.5 0.3 0.2 30 0.8 0 1\n";
    constexpr int kSpheres = 1500;
    for (int i = 0; i < kSpheres; ++i) {
        const double f = static_cast<double>(i) / kSpheres;
        const double angle = 12 * 3.141592653589793 * f;
        const double radius = 0.9 * (1 - 0.93 * f);
        const Vec3 c{1.6 * (1 - f) * std::cos(angle), 1 + 0.4 * std::sin(3 * angle) * (1 - f),
                     1.6 * (1 - f) * std::sin(angle)};
        const int copies = i % 10 == 0 ? 2 : 1;
        for (int k = 0; k < copies; ++k)
            text << "1 " << radius << ' ' << c.x << ' ' << c.y << ' ' << c.z << surface;
        if (i % 50 == 0)
            text << "3 " << c.x << ' ' << c.y << ' ' << c.z << " 0 1 0 " << radius * 0.5 << surface;
        targets.push_back(c);
        targets.push_back(c + random.unit_vector() * radius);
    }
    return text.str();
}

TEST(overlapping_spheres_culled_give_the_linear_scans_answers) {
    Random random(404);
    std::ostringstream text;
    std::vector<Vec3> targets;
    text << rt_test::kTestViewer << spiral_of_spheres(random, targets);
    const Scene scene = parse_scene(text.str());
    CHECK(scene.index->culls_spheres());
    CHECK_EQ(disagreements(scene, random, 6000, targets), 0);
    // Spheres apart, in small leaves, are not culled: there the cull costs more than it saves.
    const Scene apart = parse_scene(SceneWriter(1).scene(500, 8));
    CHECK(!apart.index->culls_spheres());
}

TEST(a_tree_of_one_node_gives_the_linear_scans_answers) {
    // Up to four bounded objects make a tree of one wide node, which is walked without the
    // stack, its children in lane order (bvh.h): the answers must not depend on that order.
    int scenes = 0, bounded_hits = 0;
    for (std::uint64_t seed = 20; seed < 60; ++seed) {
        const int objects = 1 + static_cast<int>(seed % 4);
        const Scene scene = parse_scene(SceneWriter(seed).scene(objects, 8));
        if (scene.index->bounded_count() > 4) continue;  // a composite of many operands
        ++scenes;
        // Half the rays aimed at the bounded objects' centres (the first two objects are
        // the floor and a plane), so that they often meet, overlap and tie.
        std::vector<Vec3> centres;
        for (std::size_t i = 2; i < scene.objects.size(); ++i) {
            const Bounds box = scene.objects[i].shape.bounds();
            centres.push_back((box.min + box.max) * 0.5);
        }
        Random random(seed * 7);
        CHECK_EQ(disagreements(scene, random, 1500, centres), 0);
        Tracer tracer(scene, {});
        for (int r = 0; r < 200; ++r) {
            const Vec3 origin = random.in_box(11);
            const Vec3 target = centres[random.next() % centres.size()];
            if (!(length(target - origin) > 0)) continue;
            const auto hit = tracer.closest_hit({origin, normalized(target - origin)});
            if (hit && hit->object - &scene.objects[0] >= 2) ++bounded_hits;
        }
    }
    CHECK(scenes > 30);
    CHECK(bounded_hits > scenes * 100);  // most aimed rays do meet a bounded object
}

TEST(a_shadow_ray_that_misses_the_only_bounded_object_still_meets_the_planes) {
    // One sphere and a floor: the sphere is the hierarchy's only object, so a shadow ray that
    // has just tried it as its last blocker does not walk the hierarchy (ObjectIndex::any).
    // Carried from ray to ray as a render carries it, the last blocker must never change an
    // answer: the floor still blocks, and the sphere still blocks once it is no longer the
    // one remembered.
    std::string text = kTestViewer;
    text += "1 1  0 0 0  100 1 0 0 0 1 1 0 1\n";
    text += "2 -2  0 1 0  100 0 1 0 0 1 1 0 1\n";
    const Scene scene = parse_scene(text);
    const ObjectIndex& index = *scene.index;
    CHECK_EQ(index.bounded_count(), std::size_t{1});
    const auto scanned = [&](const Ray& ray, Interval range) {
        return std::any_of(scene.objects.begin(), scene.objects.end(),
                           [&](const Object& o) { return o.shape.intersect_any(ray, range); });
    };
    LastBlocker last;
    Random random(91);
    int differ = 0, blocked = 0, open = 0;
    for (int r = 0; r < 4000; ++r) {
        const Ray ray{random.in_box(4), random.unit_vector()};
        const Interval range{1e-9, random.uniform(0.1, 10)};
        const bool answer = scanned(ray, range);
        if (index.any(ray, range, &last) != answer) ++differ;
        ++(answer ? blocked : open);
    }
    CHECK_EQ(differ, 0);
    CHECK(blocked > 500 && open > 500);
    // The sphere remembered and missed, the floor ahead: blocked; nothing ahead: open.
    last.entry = 0;
    CHECK(index.any({{5, 0, 0}, {0, -1, 0}}, {1e-9, 10}, &last));
    CHECK_EQ(last.entry, std::uint32_t{1});  // the floor, the entry after the bounded one
    last.entry = 0;
    CHECK(!index.any({{5, 0, 0}, {0, 1, 0}}, {1e-9, 10}, &last));
    // The floor remembered and missed, the sphere ahead: blocked.
    last.entry = 1;
    CHECK(index.any({{0, 5, 0}, {0, -1, 0}}, {1e-9, 4.5}, &last));
}

TEST(a_blocker_that_lets_a_ray_pass_is_forgotten_unless_a_sphere) {
    // A disk at x = 10 and a sphere at the origin: a shadow ray that passes forgets the
    // remembered disk (ObjectIndex::any), so the next one does not ask it first, and keeps
    // the remembered sphere, cheap to ask again. What blocks is remembered either way.
    std::string text = kTestViewer;
    text += "3  10 0 0  1 0 0  1  100 1 0 0 0 1 1 0 1\n";
    text += "1 1  0 0 0  100 1 0 0 0 1 1 0 1\n";
    const Scene scene = parse_scene(text);
    const ObjectIndex& index = *scene.index;
    const Interval range{1e-9, 100};
    const Ray to_disk{{5, 0, 0}, {1, 0, 0}}, to_sphere{{0, 5, 0}, {0, -1, 0}};
    const Ray up{{5, 0, 0}, {0, 1, 0}};  // meets neither
    LastBlocker disk, sphere;
    CHECK(index.any(to_disk, range, &disk));
    CHECK(index.any(to_sphere, range, &sphere));
    CHECK(disk.entry != LastBlocker{}.entry && sphere.entry != LastBlocker{}.entry);
    LastBlocker last = disk;
    CHECK(!index.any(up, range, &last));
    CHECK_EQ(last.entry, LastBlocker{}.entry);
    std::uint64_t tests = 0;
    CHECK(!index.any(up, range, &last, &tests));  // nothing asked ahead of the walk
    CHECK_EQ(tests, std::uint64_t{0});
    last = sphere;
    CHECK(!index.any(up, range, &last));
    CHECK_EQ(last.entry, sphere.entry);
    CHECK(index.any(to_disk, range, &last));
    CHECK_EQ(last.entry, disk.entry);
}

TEST(a_mesh_that_blocked_last_is_asked_again_only_behind_its_box) {
    // A mesh (a square of two triangles at x = 10), a sphere and a floor. A mesh remembered
    // as a light's last blocker is not tried ahead of the walk (ObjectIndex::any): a shadow
    // ray that misses its box never asks it. A sphere remembered is tried first, as before.
    // Either way every answer is the scan's.
    std::string text = kTestViewer;
    text += "14 4 2  10 -1 -1  10 1 -1  10 1 1  10 -1 1  0 1 2  0 2 3  100 1 0 0 0 1 1 0 1\n";
    text += "1 1  0 0 0  100 1 0 0 0 1 1 0 1\n";
    text += "2 -2  0 1 0  100 0 1 0 0 1 1 0 1\n";
    const Scene scene = parse_scene(text);
    const ObjectIndex& index = *scene.index;
    CHECK_EQ(index.bounded_count(), std::size_t{2});
    const auto asked = [&](const Ray& ray, Interval range, LastBlocker& last, bool& blocked) {
        std::uint64_t tests = 0;
        blocked = index.any(ray, range, &last, &tests);
        return tests;
    };
    const Interval range{1e-9, 100};
    const Ray to_mesh{{5, 0, 0}, {1, 0, 0}}, to_sphere{{0, 5, 0}, {0, -1, 0}};
    const Ray up{{5, 0, 0}, {0, 1, 0}};  // misses both boxes and the floor
    bool blocked = false;
    LastBlocker mesh_last;
    asked(to_mesh, range, mesh_last, blocked);
    CHECK(blocked);
    LastBlocker sphere_last;
    const Interval above_floor{1e-9, 6};  // the sphere at 4, the floor at 7
    asked(to_sphere, above_floor, sphere_last, blocked);
    CHECK(blocked);
    CHECK(mesh_last.entry != sphere_last.entry);
    // Only the floor is asked when the mesh is remembered; the sphere is tried, then the floor.
    LastBlocker last = mesh_last;
    CHECK_EQ(asked(up, range, last, blocked), std::uint64_t{1});
    CHECK(!blocked);
    last = sphere_last;
    CHECK_EQ(asked(up, range, last, blocked), std::uint64_t{2});
    CHECK(!blocked);
    // Remembered, the mesh still blocks, and the sphere blocks whichever is remembered.
    last = mesh_last;
    CHECK(index.any(to_mesh, range, &last));
    CHECK_EQ(last.entry, mesh_last.entry);
    CHECK(index.any(to_sphere, above_floor, &last));
    CHECK_EQ(last.entry, sphere_last.entry);
    // Carried from ray to ray, the answers are the scan's.
    Random random(57);
    int differ = 0, yes = 0, no = 0;
    for (int r = 0; r < 4000; ++r) {
        const Ray ray{random.in_box(12), random.unit_vector()};
        const Interval span{1e-9, random.uniform(0.1, 20)};
        const bool answer =
            std::any_of(scene.objects.begin(), scene.objects.end(),
                        [&](const Object& o) { return o.shape.intersect_any(ray, span); });
        if (index.any(ray, span, &last) != answer) ++differ;
        ++(answer ? yes : no);
    }
    CHECK_EQ(differ, 0);
    CHECK(yes > 500 && no > 500);
}

// A mesh of `triangles` random triangles within [-2, 2]^3 (ID 14), or with a random unit
// normal at each vertex (ID 16), and a surface.
std::string random_mesh(Random& random, int triangles, bool smooth) {
    std::ostringstream text;
    text.precision(17);
    const int vertices = triangles * 3;
    text << (smooth ? 16 : 14) << " " << vertices << " " << triangles << "\n";
    for (int v = 0; v < vertices; ++v) {
        const Vec3 p = random.in_box(2);
        text << p.x << " " << p.y << " " << p.z;
        if (smooth) {
            const Vec3 n = random.unit_vector();
            text << "  " << n.x << " " << n.y << " " << n.z;
        }
        text << "\n";
    }
    for (int t = 0; t < triangles; ++t)
        text << 3 * t << " " << 3 * t + 1 << " " << 3 * t + 2 << "\n";
    text << "100 1 0 0 0 1 1 0 1\n";
    return text.str();
}

TEST(a_lone_mesh_is_asked_directly_and_answers_as_the_scan) {
    // A scene whose one bounded object is a mesh (a model, alone or on a floor) asks the mesh
    // without testing its box first (ObjectIndex, lone_outline_): the mesh's own walk turns
    // away a ray outside its box. The answers must be the linear scan's, for rays that
    // miss the box as for rays aimed into it; a mesh in a frame still waits behind its box.
    const std::string floor = "2 -3  0 1 0  100 0 1 0 0 1 1 0 1\n";
    const std::string frame = "7  0.5 0 0  1 0 0  0 1 0  0 0 1  ";
    Random random(404);
    for (int variant = 0; variant < 6; ++variant) {
        const bool smooth = variant % 2 == 1, on_floor = variant >= 2, framed = variant >= 4;
        std::string text = kTestViewer;
        if (on_floor) text += floor;
        text += (framed ? frame : "") + random_mesh(random, 300, smooth);
        const Scene scene = parse_scene(text);
        const ObjectIndex& index = *scene.index;
        CHECK_EQ(index.bounded_count(), std::size_t{1});
        CHECK_EQ(scene.objects.back().shape.own_hierarchy(), !framed);
        CHECK_EQ(disagreements(scene, random, 3000, {{0, 0, 0}, {1, 1, 1}, {-1, 0.5, -1}}), 0);
        // A ray far from the mesh's box: asked directly unless framed; the floor is asked always.
        const Ray away{{50, 50, 50}, {0, 0, 1}};
        std::uint64_t tests = 0;
        ObjectIndex::Found found;
        index.closest(away, {1e-9, kInfinity}, found, &tests);
        CHECK_EQ(tests, std::uint64_t{(on_floor ? 1u : 0u) + (framed ? 0u : 1u)});
        tests = 0;
        CHECK(!index.any(away, {1e-9, 100}, nullptr, &tests));
        CHECK_EQ(tests, std::uint64_t{(on_floor ? 1u : 0u) + (framed ? 0u : 1u)});
    }
}

// Meshes among other objects (14 flat and 16 smooth, one in a frame, overlapping spheres, a
// polygon and one another) are walked with the ray the object hierarchy's walk prepared
// (ObjectIndex, hands_on_ray): the nearest hits and the shadows must be the linear scan's,
// with half the rays aimed at the meshes. Only where a mesh is reached through the walk is
// the ray handed on: not for a lone mesh, nor in a scene without one.
TEST(meshes_among_objects_walked_with_the_object_walks_ray_answer_as_the_scan) {
    Random random(405);
    for (int variant = 0; variant < 2; ++variant) {
        std::string text = kTestViewer;
        text += "2 -3  0 1 0  100 0 1 0 0 1 1 0 1\n";
        text += "7  4 0 0  1 0 0  0 1 0  0 0 1  " + random_mesh(random, 400, variant == 1);
        // The frame's mesh is asked as before; these three are handed the walk's ray.
        for (int m = 0; m < 3; ++m) text += random_mesh(random, 300, (m + variant) % 2 == 1);
        for (int i = 0; i < 40; ++i) {
            const Vec3 c = random.in_box(4);
            text += "1 " + std::to_string(random.uniform(0.1, 1)) + " " + std::to_string(c.x) +
                    " " + std::to_string(c.y) + " " + std::to_string(c.z) +
                    "\n100 0 1 0 0 1 1 0 1\n";
        }
        text += "11 4  -5 -1 -5  5 -1 -5  5 -1 5  -5 -1 5\n100 0 0 1 0 1 1 0 1\n";
        const Scene scene = parse_scene(text);
        CHECK(scene.index->hands_on_ray());
        CHECK_EQ(disagreements(scene, random, 4000, {{0, 0, 0}, {-3, 1, 0}, {3, 1, 2}, {4, 0, 0}}),
                 0);
    }
    {
        // Among spheres the index culls, its culling queries hand the ray on as well.
        std::vector<Vec3> targets;
        const std::string text = kTestViewer + spiral_of_spheres(random, targets) +
                                 random_mesh(random, 300, false) + random_mesh(random, 300, true);
        for (int i = 0; i < 200; ++i) targets.push_back(random.in_box(2));
        const Scene scene = parse_scene(text);
        CHECK(scene.index->hands_on_ray() && scene.index->culls_spheres());
        CHECK_EQ(disagreements(scene, random, 4000, targets), 0);
    }
    // Nothing to hand the ray to: spheres only, or a lone mesh (asked without a walk).
    CHECK(!parse_scene(kTestViewer + std::string("1 1 0 0 0\n100 1 0 0 0 1 1 0 1\n"))
               .index->hands_on_ray());
    CHECK(!parse_scene(kTestViewer + random_mesh(random, 50, false)).index->hands_on_ray());
}

TEST(many_parts_marks_meshes_and_composites_through_frames) {
    // The column that keeps a last blocker from being asked ahead of its box (Shape::many_parts).
    const std::string surface = " 100 1 0 0 0 1 1 0 1\n";
    const std::string frame = "7  0 0 0  1 0 0  0 1 0  0 0 1  ";
    const std::string mesh = "14 3 1  0 0 0  1 0 0  0 1 0  0 1 2";
    const std::string sphere = "1 1  0 0 0";
    const std::string solid = "20  1 1  0 0 0" + surface + "  12 0 0 0 1 1 1" + surface;
    std::string text = kTestViewer;
    for (const std::string& object : {mesh + surface, frame + mesh + surface, solid, frame + solid,
                                      sphere + surface, frame + sphere + surface})
        text += object;
    const Scene scene = parse_scene(text);
    CHECK_EQ(scene.objects.size(), std::size_t{6});
    const bool expected[] = {true, true, true, true, false, false};
    for (std::size_t i = 0; i < scene.objects.size(); ++i)
        CHECK_EQ(scene.objects[i].shape.many_parts(), expected[i]);
}

TEST(any_hit_agrees_with_the_nearest_hit_for_every_primitive) {
    const Scene scene = parse_scene(SceneWriter(11).scene(1500, 8));
    Random random(12);
    int differ = 0, hits = 0;
    for (const Object& object : scene.objects) {
        // Rays from anywhere toward the object's box (near its centre, and past its edges).
        const Bounds box = object.shape.bounds();
        const bool bounded = std::isfinite(box.min.x + box.max.x + box.min.y + box.max.y);
        const Vec3 centre = bounded ? (box.min + box.max) * 0.5 : Vec3{};
        const double reach = bounded ? length(box.max - box.min) : 10;
        for (int r = 0; r < 40; ++r) {
            const Vec3 origin = random.in_box(12);
            const Vec3 target = centre + random.in_box(0.5 * reach);
            if (!(length(target - origin) > 0)) continue;
            const Ray ray{origin, normalized(target - origin)};
            const Interval range{random.uniform(0, 1e-3), random.uniform(0.5, 40)};
            Hit hit;
            const bool nearest = object.shape.intersect(ray, range, hit);
            hits += nearest ? 1 : 0;
            if (nearest != object.shape.intersect_any(ray, range)) ++differ;
        }
    }
    CHECK_EQ(differ, 0);
    CHECK(hits > 5000);  // about 8,600: the rays do reach the objects
}

TEST(same_image_as_the_linear_scan_on_any_thread_count) {
    const Scene scene = parse_scene(SceneWriter(7).scene(2000, 40));
    RenderOptions options;
    options.max_depth = 4;
    RenderOptions linear = options;
    linear.accelerate = false;
    linear.threads = 1;
    const Raster expected = render(scene, linear);
    for (const int threads : {1, 2, 3, 8}) {
        options.threads = threads;
        CHECK(same_image(render(scene, options), expected));
    }
    // Every render mode takes the same first hit.
    for (const RenderMode mode : {RenderMode::depth, RenderMode::colour, RenderMode::normal}) {
        options.mode = linear.mode = mode;
        CHECK(same_image(render(scene, options), render(scene, linear)));
    }
}

TEST(same_image_for_every_example_scene) {
    for (const auto& entry : std::filesystem::directory_iterator(RT_SOURCE_DIR "/scenes")) {
        if (entry.path().extension() != ".in") continue;
        Scene scene = read_scene_file(entry.path().string());
        if (!RT_MEASURES_MEMORY) {
            // Under ASan, a quarter of the pixels: every scene's objects are still met, and
            // the two renders must still agree (test_golden renders them whole there).
            scene.viewer.xres = std::max(1, scene.viewer.xres / 2);
            scene.viewer.yres = std::max(1, scene.viewer.yres / 2);
        }
        RenderOptions linear;
        linear.accelerate = false;
        const bool same = same_image(render(scene, {}), render(scene, linear));
        if (!same) record_failure(__FILE__, __LINE__, entry.path().string() + " differs");
    }
}

TEST(ties_go_to_the_object_earlier_in_the_file) {
    // Two coincident spheres, many copies in between so they land in different leaves.
    std::string text = kTestViewer;
    text += "1 1  0 0 0  100 1 0 0 0 1 1 0 1\n";
    for (int i = 0; i < 200; ++i)
        text += object_text(1, {0.1, -5 + 0.05 * i, 3, -2}) + " 100 0 1 0 0 1 1 0 1\n";
    text += "1 1  0 0 0  100 0 0 1 0 1 1 0 1\n";
    const Scene scene = parse_scene(text);
    const auto found = Tracer(scene, {}).closest_hit({{0, 0, 5}, {0, 0, -1}});
    CHECK(found && found->object == &scene.objects.front());
}

TEST(counts_rays_of_each_kind) {
    // One sphere filling a 4x4 image, one light, a mirror: every primary ray hits, casts a
    // shadow ray and spawns a reflected ray that escapes (and casts no shadow ray).
    const Scene scene = parse_scene(std::string("102  0 0 5  0 0 0  0.1 0 0  0 0.1 0  4 4\n") +
                                    "1 1 0 0 0  100 1 1 1 0.5 10 0.5 0 1\n104 0 0 10  1 1 1\n");
    RenderStats stats;
    RenderOptions options;
    options.threads = 2;
    render(scene, options, &stats);
    CHECK_EQ(stats.primary_rays, 16u);
    CHECK_EQ(stats.shadow_rays, 16u);
    CHECK_EQ(stats.secondary_rays(), 16u);
}

TEST(a_tracer_needs_the_index_unless_linear) {
    std::istringstream in(std::string(kTestViewer) + "1 1 0 0 0 100 1 1 1 0 1 1 0 1\n");
    SceneReader reader(in, "test.in", {});
    const Scene scene = reader.read_scene();  // not indexed
    bool threw = false;
    try {
        Tracer(scene, {});
    } catch (const std::logic_error&) {
        threw = true;
    }
    CHECK(threw);
    CHECK(Tracer(scene, linear_options()).closest_hit({{0, 0, 5}, {0, 0, -1}}).has_value());
}
