// The wide hierarchy: its structure, its float box test (vector and scalar) against the
// double one, and the mesh's packed leaves against a scan of every triangle. The float test
// may keep more boxes than the double test but never fewer, and whatever it keeps, the hit
// found must be the scan's to the bit: on seeded random rays with zero direction components,
// origins inside boxes and on their faces, and coordinates from 1e-30 to 1e25.
#include <algorithm>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <vector>

#include "accel/bvh.h"
#include "check.h"
#include "primitives/mesh_core.h"
#include "primitives/watertight.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

using BoxTest = Bvh::BoxTest;

std::vector<Bounds> random_boxes(Random& random, std::size_t count, double spread, double size) {
    std::vector<Bounds> boxes;
    for (std::size_t i = 0; i < count; ++i) {
        const Vec3 c = random.in_box(spread);
        Vec3 h{random.uniform(0, size), random.uniform(0, size), random.uniform(0, size)};
        if (i % 5 == 0) h.y = 0;  // flat
        boxes.push_back({c - h, c + h});
    }
    return boxes;
}

Vec3 scaled(const Vec3& v, double s) { return {v.x * s, v.y * s, v.z * s}; }

// A direction with, now and then, one or two components exactly zero (rays parallel to
// slabs), or a component far smaller than the others.
Vec3 awkward_direction(Random& random, int i) {
    Vec3 d = random.unit_vector();
    switch (i % 6) {
        case 0:
            d.x = 0;
            break;
        case 1:
            d.y = d.z = 0;
            break;
        case 2:
            d.z = d.z * 1e-20;
            break;
        default:
            break;
    }
    if (d == Vec3{}) d = {0, 0, 1};
    return d;
}

// random_boxes(random, count, 10, 0.7) scaled by `scale`.
std::vector<Bounds> scaled_random_boxes(Random& random, std::size_t count, double scale) {
    std::vector<Bounds> boxes = random_boxes(random, count, 10, 0.7);
    for (Bounds& b : boxes) b = {scaled(b.min, scale), scaled(b.max, scale)};
    return boxes;
}

// Ray r of a traversal test over `boxes` (scaled by `scale`): from a random point, or every
// fourth from a box's corner, in an awkward direction.
Ray awkward_ray(Random& random, int r, const std::vector<Bounds>& boxes, double scale) {
    Vec3 origin = scaled(random.in_box(12), scale);
    if (r % 4 == 0) origin = boxes[random.next() % boxes.size()].min;  // on a corner
    return {origin, awkward_direction(random, r)};
}

// Checks every wide node below `index`: children in use from the first lane, leaves small,
// each interior lane's box holding its node's boxes, each leaf lane's box holding its
// primitives' boxes; marks the leaves' primitives seen.
void check_wide(const Bvh& bvh, std::span<const Bounds> boxes, std::uint32_t index,
                std::vector<int>& seen) {
    const WideNode& node = bvh.wide_nodes()[index];
    CHECK(node.size >= 1 && node.size <= WideNode::kWidth);
    for (int i = 0; i < WideNode::kWidth; ++i) {
        const Bounds lane{{node.box[0][i], node.box[1][i], node.box[2][i]},
                          {node.box[3][i], node.box[4][i], node.box[5][i]}};
        if (i >= node.size) {
            CHECK(!(lane.min.x <= lane.max.x));  // unused: empty
            continue;
        }
        if (node.is_leaf(i)) {
            CHECK(node.count[i] <= Bvh::kMaxLeafSize);
            for (std::uint32_t p = node.child[i]; p < node.child[i] + node.count[i]; ++p) {
                const Bounds& b = boxes[bvh.order()[p]];
                CHECK(lane.contains(b.min) && lane.contains(b.max));
                ++seen[p];
            }
            continue;
        }
        CHECK(node.child[i] > index && node.child[i] < bvh.wide_nodes().size());
        const WideNode& below = bvh.wide_nodes()[node.child[i]];
        for (int j = 0; j < below.size; ++j)
            CHECK(lane.contains({below.box[0][j], below.box[1][j], below.box[2][j]}) &&
                  lane.contains({below.box[3][j], below.box[4][j], below.box[5][j]}));
        check_wide(bvh, boxes, node.child[i], seen);
    }
}

// What traversal offers for one ray (no pruning): a flag per primitive in leaf order.
template <BoxTest Test>
std::vector<bool> offered(const Bvh& bvh, const Ray& ray, double t_min, double t_max) {
    std::vector<bool> seen(bvh.order().size(), false);
    double limit = t_max;
    bvh.closest<Test>(ray, t_min, limit, [&](std::uint32_t i) { seen[i] = true; });
    return seen;
}

bool superset(const std::vector<bool>& big, const std::vector<bool>& small) {
    for (std::size_t i = 0; i < big.size(); ++i)
        if (small[i] && !big[i]) return false;
    return true;
}

}  // namespace

// max_abs_component (which the builder's padding and every query's tolerance use) must give
// std::fmax's answer to the bit, NaN rule included, though it no longer calls it.
TEST(max_abs_component_is_fmax_of_the_magnitudes_to_the_bit) {
    std::vector<double> values = {0.0,       -0.0,         0x1p-1074,     -0x1p-1074, DBL_MIN,
                                  1.0,       -1.0,         DBL_MAX,       -DBL_MAX,   HUGE_VAL,
                                  -HUGE_VAL, std::nan(""), -std::nan(""), 2.5e-300,   1e300};
    Random random(77);
    for (int i = 0; i < 200; ++i)
        values.push_back(
            std::ldexp(random.uniform(-1, 1), static_cast<int>(random.next() % 2000) - 1000));
    const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
    int checked = 0;
    for (const double x : values)
        for (const double y : values) {
            const double z = values[static_cast<std::size_t>(checked) % values.size()];
            const double expected = std::fmax(std::fabs(x), std::fmax(std::fabs(y), std::fabs(z)));
            const double got = max_abs_component({x, y, z});
            if (std::isnan(expected)) {
                CHECK(std::isnan(got));
            } else {
                CHECK_EQ(bits(got), bits(expected));
            }
            ++checked;
        }
    CHECK(checked > 40000);
}

TEST(wide_nodes_hold_every_leaf_once_and_nest) {
    Random random(21);
    for (const std::size_t n : {1, 2, 5, 9, 100, 5000, 40000}) {
        const std::vector<Bounds> boxes = random_boxes(random, n, 10, 1);
        const Bvh bvh(boxes);
        std::vector<int> seen(n, 0);
        check_wide(bvh, boxes, 0, seen);
        CHECK(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
        // Each wide node replaces at least one binary interior node (a lone leaf: one node).
        CHECK(bvh.wide_nodes().size() <= std::max<std::size_t>(1, bvh.nodes().size() / 2));
        if (n >= 5000) CHECK(bvh.wide_nodes().size() * 5 < bvh.nodes().size() * 2);
    }
    CHECK(Bvh().wide_nodes().empty());
}

TEST(the_same_wide_tree_on_any_number_of_threads) {
    Random random(25);
    const std::vector<Bounds> boxes = random_boxes(random, 120000, 50, 0.5);
    const Bvh one(boxes, 1);
    for (const int threads : {2, 3}) {
        const Bvh many(boxes, threads);
        CHECK_EQ(many.wide_nodes().size(), one.wide_nodes().size());
        CHECK(std::memcmp(many.wide_nodes().data(), one.wide_nodes().data(),
                          one.wide_nodes().size() * sizeof(WideNode)) == 0);
    }
}

TEST(float_lanes_keep_every_box_the_double_test_keeps) {
    // One wide node of up to eight boxes at a time, compared lane by lane.
    Random random(22);
    int kept_exact = 0, kept_float = 0, failures = 0;
    for (int r = 0; r < 200000; ++r) {
        const double scale = std::ldexp(1.0, static_cast<int>(random.next() % 181) - 100);
        WideNode node{};
        node.size = static_cast<std::uint8_t>(1 + random.next() % WideNode::kWidth);
        for (int i = 0; i < WideNode::kWidth; ++i)
            for (int k = 0; k < 3; ++k) {
                double lo = random.uniform(-2, 2), hi = lo + random.uniform(0, 2);
                if (random.next() % 4 == 0) hi = lo;  // flat
                node.box[k][i] = static_cast<float>(lo * scale);
                node.box[3 + k][i] = static_cast<float>(hi * scale);
                if (i >= node.size) node.box[k][i] = HUGE_VALF, node.box[3 + k][i] = -HUGE_VALF;
            }
        // Origins inside a box, on its faces, or anywhere near; directions awkward.
        Vec3 origin = scaled(random.in_box(3), scale);
        const int lane = static_cast<int>(random.next() % node.size);
        if (r % 3 == 0) {
            double on_face[3];
            for (int k = 0; k < 3; ++k)
                on_face[k] = random.next() % 2 ? node.box[k][lane] : node.box[3 + k][lane];
            origin = {on_face[0], on_face[1], on_face[2]};
        }
        Vec3 direction = awkward_direction(random, r);
        if (r % 2 == 1) {  // toward a box's middle
            const int aim = static_cast<int>(random.next() % node.size);
            const Vec3 middle{0.5 * node.box[0][aim] + 0.5 * node.box[3][aim],
                              0.5 * node.box[1][aim] + 0.5 * node.box[4][aim],
                              0.5 * node.box[2][aim] + 0.5 * node.box[5][aim]};
            if (max_abs_component(middle - origin) > 0) direction = normalized(middle - origin);
        }
        const Ray ray{origin, direction};
        const double t_min = r % 4 == 0 ? 0 : random.uniform(0, 2) * scale;
        const double t_max = r % 5 == 0 ? kInfinity : t_min + random.uniform(0, 5) * scale;
        const WideRay wide(ray, t_min);
        CHECK(wide.usable());
        const BoxRay exact(ray);
        float enter_simd[WideNode::kWidth], enter_scalar[WideNode::kWidth];
        float enter_eight[WideNode::kWidth];
        const unsigned simd = wide.enters<4>(node, t_max, enter_simd);
        const unsigned scalar = wide.enters<1>(node, t_max, enter_scalar);
        const unsigned eight = wide.enters<8>(node, t_max, enter_eight);
        if (simd != scalar || eight != scalar) ++failures;
        for (int i = 0; i < node.size; ++i) {
            const float bound[6] = {node.box[0][i], node.box[1][i], node.box[2][i],
                                    node.box[3][i], node.box[4][i], node.box[5][i]};
            double t = 0;
            if (!exact.enters(bound, t_min, t_max, t)) continue;
            ++kept_exact;
            if ((simd >> i & 1u) == 0 || !(enter_simd[i] <= t)) {
                ++failures;
                std::cerr << "dropped: ray " << show(ray.origin) << ' ' << show(ray.direction)
                          << " lane " << i << " enters at " << t << "\n";
            }
            if (enter_simd[i] != enter_scalar[i] || enter_eight[i] != enter_scalar[i]) ++failures;
        }
        kept_float += std::popcount(simd);
    }
    CHECK_EQ(failures, 0);
    CHECK(kept_exact > 50000);
    // Conservative, but not by much: the float test keeps few boxes the double test drops.
    CHECK(kept_float < kept_exact + kept_exact / 50);
}

TEST(rays_beyond_float_range_take_the_double_test) {
    CHECK(!WideRay(Ray{{1e31, 0, 0}, {1, 0, 0}}, 0).usable());
    CHECK(!WideRay(Ray{{0, 0, 0}, {1, 1e-40, 0}}, 0).usable());  // 1e40 overflows a float
    CHECK(!WideRay(Ray{{0, 0, 0}, {1, 0, 0}}, kInfinity).usable());
    CHECK(WideRay(Ray{{0, 0, 0}, {1, 0, 0}}, 0).usable());  // a zero component is fine
    // Such a ray still finds its box.
    const std::vector<Bounds> boxes{{{2e30, -1, -1}, {3e30, 1, 1}}, {{-5, -5, -5}, {5, 5, 5}}};
    const Bvh bvh(boxes);
    const std::vector<bool> seen =
        offered<BoxTest::simd>(bvh, {{1e31, 0, 0}, {-1, 0, 0}}, 0, kInfinity);
    CHECK(std::count(seen.begin(), seen.end(), true) == 2);
}

TEST(vector_scalar_and_double_traversals_offer_the_same_boxes) {
    Random random(23);
    for (const double scale : {1e-30, 1.0, 1e25}) {
        const std::vector<Bounds> boxes = scaled_random_boxes(random, 3000, scale);
        const Bvh bvh(boxes);
        int failures = 0;
        for (int r = 0; r < 1500; ++r) {
            const Ray ray = awkward_ray(random, r, boxes, scale);
            const double t_max = r % 2 ? kInfinity : random.uniform(1, 20) * scale;
            const auto exact = offered<BoxTest::exact>(bvh, ray, 0, t_max);
            const auto simd = offered<BoxTest::simd>(bvh, ray, 0, t_max);
            const auto four = offered<BoxTest::four>(bvh, ray, 0, t_max);
            const auto eight = offered<BoxTest::eight>(bvh, ray, 0, t_max);
            const auto scalar = offered<BoxTest::scalar>(bvh, ray, 0, t_max);
            if (simd != scalar || four != scalar || eight != scalar || !superset(simd, exact))
                ++failures;
        }
        CHECK_EQ(failures, 0);
    }
}

namespace {

// A mesh of random triangles (some sharing edges, some coincident, some tiny) scaled by
// `scale`, built through mesh_core as a mesh primitive does.
mesh_core::Core random_mesh(Random& random, int triangles, double scale) {
    mesh_core::Core core;
    for (int i = 0; i < triangles; ++i) {
        const Vec3 c = random.in_box(8);
        const double size = i % 7 == 0 ? 1e-3 : random.uniform(0.2, 2);
        for (int v = 0; v < 3; ++v) core.vertices.push_back(scaled(c + random.in_box(size), scale));
    }
    // Some triangles reuse the previous one's edge or repeat it exactly (ties).
    mesh_core::build(core, triangles, 1, [&](long i) {
        const auto base = static_cast<std::uint32_t>(3 * i);
        if (i > 0 && i % 9 == 0) return std::array<std::uint32_t, 3>{base - 3, base - 2, base - 1};
        if (i > 0 && i % 4 == 0) return std::array<std::uint32_t, 3>{base - 3, base - 2, base};
        return std::array<std::uint32_t, 3>{base, base + 1, base + 2};
    });
    return core;
}

// The nearest hit by testing every triangle: the smallest t, then the earliest in the file.
bool scan_closest(const mesh_core::Core& core, const Ray& ray, Interval range, Hit& hit) {
    const TriangleRay triangle_ray(ray);
    bool found = false;
    std::uint32_t best_place = 0;
    for (std::size_t i = 0; i < core.triangles.size(); ++i) {
        const mesh_core::Triangle& tri = core.triangles[i];
        double t = 0;
        if (!triangle_ray.crosses(core.vertex(tri, 0), core.vertex(tri, 1), core.vertex(tri, 2),
                                  t) ||
            !range.contains(t))
            continue;
        if (!found || t < hit.t || (t == hit.t && tri.place() < best_place)) {
            found = true;
            hit = {t, static_cast<int>(i)};
            best_place = tri.place();
        }
    }
    return found;
}

}  // namespace

TEST(packed_mesh_leaves_find_the_scans_hit_to_the_bit) {
    Random random(24);
    for (const double scale : {1e-20, 1.0, 1e20}) {
        const mesh_core::Core core = random_mesh(random, 4000, scale);
        CHECK(core.packed.size() == core.triangles.size());
        int hits = 0, failures = 0;
        for (int r = 0; r < 4000; ++r) {
            // From outside, from inside the mesh's box, and from a vertex.
            Vec3 origin = scaled(random.in_box(r % 3 == 0 ? 20 : 8), scale);
            if (r % 10 == 0) origin = core.vertices[random.next() % core.vertices.size()];
            const Ray ray{origin, awkward_direction(random, r)};
            const Interval range{r % 2 ? 0 : 1e-9 * scale,
                                 r % 3 ? kInfinity : random.uniform(1, 30) * scale};
            Hit fast, slow;
            const bool a = mesh_core::closest(core, ray, range, fast);
            const bool b = scan_closest(core, ray, range, slow);
            hits += b ? 1 : 0;
            if (a != b || (a && (std::bit_cast<std::uint64_t>(fast.t) !=
                                     std::bit_cast<std::uint64_t>(slow.t) ||
                                 fast.part != slow.part)))
                ++failures;
            if (mesh_core::any(core, ray, range) != b) ++failures;
            // Given the ray as a walk above would have prepared it (the object hierarchy's,
            // ObjectIndex), the mesh answers the same.
            const WideRay prepared(ray, range.t_min);
            if (prepared.usable()) {
                Hit handed;
                const bool c = mesh_core::closest(core, ray, range, handed, &prepared);
                if (c != a || (c && (std::bit_cast<std::uint64_t>(handed.t) !=
                                         std::bit_cast<std::uint64_t>(fast.t) ||
                                     handed.part != fast.part)))
                    ++failures;
                if (mesh_core::any(core, ray, range, &prepared) != b) ++failures;
            }
        }
        CHECK_EQ(failures, 0);
        CHECK(hits > 1000);
    }
}

namespace {

// The leaves a walk visits, in order, as (first, count) pairs, and the prepared ray each was
// told of (null or not).
struct Visits {
    std::vector<std::uint32_t> leaves;
    int told = 0, untold = 0;

    void visit(std::uint32_t first, std::uint32_t count, const WideRay* walked) {
        leaves.push_back(first);
        leaves.push_back(count);
        ++(walked != nullptr ? told : untold);
    }
};

}  // namespace

// A walk handed the ray prepared for it (Bvh::closest_leaves' `prepared`: a mesh's walk below
// the object hierarchy's) visits exactly the leaves, in exactly the order, that it visits
// preparing the ray itself; and a walk tells each leaf the ray it prepared, which is that
// same ray: handed on to a second walk, it visits the same leaves again.
TEST(a_walk_handed_its_prepared_ray_visits_what_it_would_visit_preparing_it) {
    Random random(31);
    for (const double scale : {1e-30, 1.0, 1e25}) {
        const std::vector<Bounds> boxes = scaled_random_boxes(random, 2000, scale);
        const Bvh bvh(boxes);
        int differ = 0, handed = 0, told_on = 0;
        for (int r = 0; r < 1500; ++r) {
            const Ray ray = awkward_ray(random, r, boxes, scale);
            const double t_min = r % 3 == 0 ? 0 : random.uniform(0, 5) * scale;
            // A t_max that falls as leaves are visited, as a nearest hit's does.
            const double start = r % 2 ? kInfinity : random.uniform(5, 20) * scale;
            const auto walk = [&](const WideRay* prepared, bool nearest, Visits& v) {
                double t_max = start;
                int step = 0;
                const auto leaf = [&](std::uint32_t first, std::uint32_t count, auto,
                                      const WideRay* walked) {
                    v.visit(first, count, walked);
                    if (++step % 3 == 0) t_max = t_max * 0.9;
                    return !nearest && step == 7;
                };
                if (nearest) {
                    if (prepared != nullptr)
                        bvh.closest_leaves(ray, t_min, t_max, leaf, prepared);
                    else
                        bvh.closest_leaves(ray, t_min, t_max, leaf);
                } else {
                    if (prepared != nullptr)
                        bvh.any_leaves(ray, t_min, t_max, leaf, prepared);
                    else
                        bvh.any_leaves(ray, t_min, t_max, leaf);
                }
            };
            const WideRay prepared(ray, t_min);
            for (const bool nearest : {true, false}) {
                Visits alone, given;
                walk(nullptr, nearest, alone);
                if (prepared.usable()) {
                    walk(&prepared, nearest, given);
                    ++handed;
                    // Every leaf is told a prepared ray, and none where the ray is unusable.
                    if (given.leaves != alone.leaves || alone.untold != 0) ++differ;
                } else if (alone.told != 0) {
                    ++differ;
                }
            }
            // The ray the walk tells its leaves is the one it would prepare: a second walk,
            // given it at the first leaf, visits what a walk preparing its own does.
            bool checked = false;
            double t_max = start;
            bvh.closest_leaves(
                ray, t_min, t_max, [&](std::uint32_t, std::uint32_t, auto, const WideRay* walked) {
                    if (checked || walked == nullptr) return;
                    checked = true;
                    Visits again, fresh;
                    double a = start, b = start;
                    bvh.closest_leaves(
                        ray, t_min, a,
                        [&](std::uint32_t f, std::uint32_t c, auto, const WideRay* w) {
                            again.visit(f, c, w);
                        },
                        walked);
                    bvh.closest_leaves(ray, t_min, b,
                                       [&](std::uint32_t f, std::uint32_t c, auto,
                                           const WideRay* w) { fresh.visit(f, c, w); });
                    if (again.leaves != fresh.leaves) ++differ;
                });
            if (checked) ++told_on;
        }
        CHECK_EQ(differ, 0);
        CHECK(handed > 2000);
        CHECK(told_on > 300);
    }
}
