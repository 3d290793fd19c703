#include "accel/object_index.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <type_traits>

#include "accel/parallel.h"
#include "primitives/sphere_test.h"
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

ObjectIndex::ObjectIndex(std::span<const Object> objects, int threads)
    : object_count_(objects.size()) {
    if (objects.size() > std::numeric_limits<std::uint32_t>::max())
        throw std::length_error("too many objects for the hierarchy");
    constexpr std::size_t kPart = 65536;  // the least a thread is worth (parallel.h)
    // Which objects have finite bounds. The bounds themselves are not kept: the hierarchy
    // asks for them again as it makes its references, which costs less than storing 48
    // bytes an object (on this machine a fresh page costs about 2.7 microseconds to touch).
    std::vector<std::uint8_t> finite(objects.size());
    parallel_parts(objects.size(), threads, kPart, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i)
            finite[i] = finite_box(objects[i].shape.bounds()) ? 1 : 0;
    });
    std::vector<std::uint32_t> bounded;
    std::vector<Entry> unbounded;
    std::size_t spheres = 0, takers = 0;
    bounded.reserve(objects.size());
    for (std::uint32_t i = 0; i < objects.size(); ++i)
        if (finite[i] != 0) {
            bounded.push_back(i);
            if (objects[i].shape.functions->sphere != nullptr) ++spheres;
            if (objects[i].shape.functions->intersect_prepared != nullptr) ++takers;
        } else {
            unbounded.push_back(entry(objects[i], i, false));
        }
    // The walk hands its ray on where an object it reaches takes it; a lone object (one
    // bounded) is asked without the walk. Every entry then holds the call the queries make:
    // the prepared one exactly where they are compiled to hand the ray on.
    if (bounded.size() > 1 && takers > 0) queries_ |= kHandsOn;
    finite = {};
    struct Source {
        std::span<const Object> objects;
        const std::vector<std::uint32_t>& bounded;
    } const source{objects, bounded};
    bvh_ = Bvh(bounded.size(),
               {&source,
                [](const void* context, std::uint32_t i) {
                    const auto& s = *static_cast<const Source*>(context);
                    return s.objects[s.bounded[i]].shape.bounds();
                }},
               threads, Bvh::node_cost(bounded.size() - spheres));
    bvh_.drop_binary_nodes();
    // Leaf order follows space, not the file. Reading the objects in leaf order would load
    // from all over memory, one object and then its parameters at a time (a million
    // spheres: 135 ns each, most of the index's build); instead the objects are read in
    // file order, where they lie one after another, and each entry is written at its
    // place in leaf order. Writes to scattered places do not hold up the loop as loads
    // do. With several threads each reads its own part.
    static_assert(std::is_trivially_default_constructible_v<Entry>);  // see entries_
    const Bvh::Order order = bvh_.take_order();
    bounded_count_ = order.size();
    std::vector<std::uint32_t, UninitializedAllocator<std::uint32_t>> place(bounded_count_);
    parallel_parts(bounded_count_, threads, kPart, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) place[order[i]] = static_cast<std::uint32_t>(i);
    });
    entries_.reserve(objects.size());
    entries_.resize(bounded_count_);
    // Each entry's line is asked for a few objects ahead: a store to a line not in cache
    // waits for it, and the processor fetches only so many at once for stores in order
    // (spheres-1m's build 0.271 -> 0.250 s on one thread, docs/performance.md; further
    // ahead gained less).
    constexpr std::size_t kAhead = 16;
    parallel_parts(bounded_count_, threads, kPart, [&](std::size_t begin, std::size_t end) {
        for (std::size_t j = begin; j < end; ++j) {
            if (j + kAhead < end) __builtin_prefetch(&entries_[place[j + kAhead]], 1);
            entries_[place[j]] = entry(objects[bounded[j]], bounded[j], hands_on_ray());
        }
    });
    entries_.insert(entries_.end(), unbounded.begin(), unbounded.end());
    if (bounded_count_ == 1) lone_outline_ = objects[bounded[0]].shape.functions->outline;
    if (spheres > 0 && cull_pays()) {
        cull_ = SphereCull(bounded_count_);
        for (std::size_t i = 0; i < bounded_count_; ++i)
            if (entries_[i].sphere) cull_.set(i, entries_[i].sphere_parameters());
        queries_ |= kCulled;
    }
}

bool ObjectIndex::cull_pays() const {
    const std::span<const WideNode> nodes = bvh_.wide_nodes();
    if (nodes.empty()) return false;
    // The SAH's measure: a ray through the root's box enters a leaf's box with the chance of
    // their areas' ratio.
    const WideNode& root = nodes[0];
    float root_bound[6] = {HUGE_VALF, HUGE_VALF, HUGE_VALF, -HUGE_VALF, -HUGE_VALF, -HUGE_VALF};
    for (int lane = 0; lane < root.size; ++lane)
        for (int k = 0; k < 3; ++k) {
            root_bound[k] = std::min(root_bound[k], root.box[k][lane]);
            root_bound[3 + k] = std::max(root_bound[3 + k], root.box[3 + k][lane]);
        }
    const double root_area = bound_half_area(root_bound);
    if (!(root_area > 0) || !std::isfinite(root_area)) return false;
    // Objects, then spheres, asked in large leaves per ray through the root's box: the
    // first from the nodes alone, so that a hierarchy far below the mark (a million spheres
    // apart) reads none of its entries here.
    const auto expected = [&](bool spheres_only) {
        double sum = 0;
        for (const WideNode& node : nodes)
            for (int lane = 0; lane < node.size; ++lane) {
                if (node.count[lane] < kCulledLeaf) continue;
                std::uint32_t asked = node.count[lane];
                if (spheres_only) {
                    asked = 0;
                    for (std::uint32_t i = node.child[lane], end = i + node.count[lane]; i < end;
                         ++i)
                        asked += entries_[i].sphere ? 1 : 0;
                }
                sum += bound_half_area(node.bound(lane).data()) / root_area * asked;
            }
        return sum;
    };
    return expected(false) >= kCulledTests && expected(true) >= kCulledTests;
}

ObjectIndex::Entry ObjectIndex::entry(const Object& object, std::uint32_t index, bool hands_on) {
    const Shape& shape = object.shape;
    Entry e{};
    e.object = index;
    e.many_parts = shape.many_parts();
    e.sphere = shape.functions->sphere != nullptr;
    e.prepared = hands_on && !e.sphere && shape.functions->intersect_prepared != nullptr;
    if (e.sphere) {
        const SphereParameters s = shape.functions->sphere(shape.data.get());
        e.test.sphere[0] = s.centre.x;
        e.test.sphere[1] = s.centre.y;
        e.test.sphere[2] = s.centre.z;
        e.test.sphere[3] = s.radius_squared;
    } else if (e.prepared) {
        e.test.prepared_call = {shape.functions->intersect_prepared,
                                shape.functions->intersect_any_prepared != nullptr
                                    ? shape.functions->intersect_any_prepared
                                    : shape.functions->intersect_prepared,
                                shape.data.get()};
    } else {
        e.test.call = {shape.intersect_function(), shape.any_hit_function(), shape.data.get()};
    }
    return e;
}

// Inlined always, as the lambdas below that call them: in the walks, which are large, GCC
// otherwise leaves them out of line (a call per object asked).
template <bool HandsOn>
[[gnu::always_inline]] inline bool ObjectIndex::hits(std::uint32_t i, const Ray& ray,
                                                     Interval range, Hit& hit,
                                                     const WideRay* walked) const {
    const Entry& e = entries_[i];
    if (e.sphere) return sphere_hit(e.sphere_parameters(), ray, range, hit);
    if (HandsOn && e.prepared)
        return e.test.prepared_call.intersect(e.test.prepared_call.data, ray, range, hit, walked);
    return e.test.call.intersect(e.test.call.data, ray, range, hit);
}

template <bool HandsOn>
[[gnu::always_inline]] inline bool ObjectIndex::blocks(std::uint32_t i, const Ray& ray,
                                                       Interval range, Hit& scratch,
                                                       const WideRay* walked) const {
    const Entry& e = entries_[i];
    if (!e.sphere) {
        if (HandsOn && e.prepared)
            return e.test.prepared_call.intersect_any(e.test.prepared_call.data, ray, range,
                                                      scratch, walked);
        return e.test.call.intersect_any(e.test.call.data, ray, range, scratch);
    }
    double t = 0;
    return sphere_crossing(e.sphere_parameters(), ray, range, t);
}

template <bool Culled, bool HandsOn>
bool ObjectIndex::closest_in(const Ray& ray, Interval range, Found& found, std::uint64_t* tests,
                             bool bounded) const {
    double best = range.t_max;
    std::uint32_t best_object = kNone;
    std::uint64_t uncounted = 0;
    std::uint64_t& asked = tests != nullptr ? *tests : uncounted;
    // The linear scan asks each object with its own best so far, and an intersect's answer
    // near t_max can depend on t_max by a rounding (an affine scales it), so each object is
    // asked a little past the best, and the answer is judged here: nearer wins, and at the
    // same distance the object earlier in the file.
    const auto limit = [&] { return best_object == kNone ? best : best + kTieSlack * best; };
    auto ask = [&](std::uint32_t i, const WideRay* walked) __attribute__((always_inline)) {
        Hit hit;
        if (!hits<HandsOn>(i, ray, {range.t_min, limit()}, hit, walked)) return;
        const std::uint32_t object = entries_[i].object;
        if (!(hit.t < best || (hit.t == best && object < best_object))) return;
        best = hit.t;
        best_object = object;
        found = {object, hit};
    };
    // (walked defaults to none, so that the walk can take test itself as its visit: through a
    // lambda around it, each object asked cost a load more.)
    auto test = [&](std::uint32_t i, const WideRay* walked = nullptr)
        __attribute__((always_inline)) {
        ++asked;
        ask(i, walked);
    };
    // The unbounded objects first: a floor under everything prunes much of the tree.
    for (auto i = static_cast<std::uint32_t>(bounded_count_); i < entries_.size(); ++i)
        test(i, nullptr);
    if (!bounded) return best_object != kNone;
    if (lone_hierarchy()) {
        test(0, nullptr);
    } else if constexpr (Culled) {
        SphereCull::Ray8 cull_ray{};
        bool prepared = false;  // only once a large leaf is reached
        auto leaf = [&](std::uint32_t first, std::uint32_t count, auto avx2, const WideRay* walked)
            __attribute__((always_inline)) {
            if (count < kCulledLeaf) {
                for (std::uint32_t i = first; i < first + count; ++i) test(i, walked);
                return;
            }
            if (!prepared) cull_ray = SphereCull::prepare(ray, range.t_min);
            prepared = true;
            // Every sphere is counted as asked, the ones the cull drops too: the
            // counts are those of the exact tests alone.
            asked += count;
            // The limit only falls as the leaf's spheres are asked: the cull's holds.
            for (unsigned keep = cull_.keep<decltype(avx2)::value>(cull_ray, first, count, limit());
                 keep != 0; keep &= keep - 1)
                ask(first + static_cast<std::uint32_t>(std::countr_zero(keep)), walked);
        };
        bvh_.closest_leaves(ray, range.t_min, best, leaf);
    } else if constexpr (HandsOn) {
        bvh_.closest_leaves(
            ray, range.t_min, best,
            [&](std::uint32_t first, std::uint32_t count, auto, const WideRay* walked)
                __attribute__((always_inline)) {
                    for (std::uint32_t i = first; i < first + count; ++i) test(i, walked);
                });
    } else {
        bvh_.closest(ray, range.t_min, best, test);
    }
    return best_object != kNone;
}

template <bool Culled, bool HandsOn>
bool ObjectIndex::any_in(const Ray& ray, Interval range, Blocker* last,
                         std::uint64_t* tests) const {
    Hit hit;
    std::uint64_t uncounted = 0;
    std::uint64_t& asked = tests != nullptr ? *tests : uncounted;
    // The last blocker is tried first; if it does not block, it is not tried again below.
    // Not one made of many parts (a mesh, CSG): asked ahead of its box it would start a
    // search of its parts on every shadow ray, most of which its box turns away; the walk
    // below reaches it behind its box instead.
    std::uint32_t tried = kNone;
    // Whether entry i blocks, where `maybe` (the cull's verdict) allows it; counted as asked
    // either way, but not the last blocker again.
    auto stops_if = [&](std::uint32_t i, bool maybe, const WideRay* walked)
        __attribute__((always_inline)) {
        if (i == tried) return false;
        ++asked;
        if (!maybe || !blocks<HandsOn>(i, ray, range, hit, walked)) return false;
        if (last != nullptr) last->entry = i;
        return true;
    };
    auto stops = [&](std::uint32_t i, const WideRay* walked = nullptr)
        __attribute__((always_inline)) {
        return stops_if(i, true, walked);
    };
    if (last != nullptr && last->entry < entries_.size() && !entries_[last->entry].many_parts) {
        if (stops(last->entry, nullptr)) return true;
        tried = last->entry;
    }
    for (auto i = static_cast<std::uint32_t>(bounded_count_); i < entries_.size(); ++i)
        if (stops(i, nullptr)) return true;
    // A hierarchy over one object that was just tried (a sphere on a floor, say; a mesh is
    // not tried ahead) has nothing more to offer: its walk would prepare the ray and test the
    // box only to skip it.
    if (bounded_count_ == 1 && tried == 0) return false;
    if (lone_hierarchy()) return stops(0, nullptr);
    if constexpr (Culled) {
        SphereCull::Ray8 cull_ray{};
        bool prepared = false;
        auto leaf = [&](std::uint32_t first, std::uint32_t count, auto avx2, const WideRay* walked)
            __attribute__((always_inline)) {
            unsigned keep = (1u << count) - 1;
            if (count >= kCulledLeaf) {
                if (!prepared) cull_ray = SphereCull::prepare(ray, range.t_min);
                prepared = true;
                keep = cull_.keep<decltype(avx2)::value>(cull_ray, first, count, range.t_max);
            }
            for (std::uint32_t k = 0; k < count; ++k)
                if (stops_if(first + k, (keep >> k & 1) != 0, walked)) return true;
            return false;
        };
        return bvh_.any_leaves(ray, range.t_min, range.t_max, leaf);
    } else if constexpr (HandsOn) {
        return bvh_.any_leaves(
            ray, range.t_min, range.t_max,
            [&](std::uint32_t first, std::uint32_t count, auto, const WideRay* walked)
                __attribute__((always_inline)) {
                    for (std::uint32_t i = first; i < first + count; ++i)
                        if (stops(i, walked)) return true;
                    return false;
                });
    } else {
        return bvh_.any(ray, range.t_min, range.t_max, stops);
    }
}

// The plain queries are called from the header; the other forms only from closest_other and
// any_other below, which instantiate them.
template bool ObjectIndex::closest_in<false, false>(const Ray&, Interval, Found&, std::uint64_t*,
                                                    bool) const;
template bool ObjectIndex::any_in<false, false>(const Ray&, Interval, Blocker*,
                                                std::uint64_t*) const;

template <class Query>
bool ObjectIndex::other_form(const Query& query) const {
    switch (queries_) {
        case kCulled:
            return query(std::true_type{}, std::false_type{});
        case kHandsOn:
            return query(std::false_type{}, std::true_type{});
        default:
            return query(std::true_type{}, std::true_type{});
    }
}

bool ObjectIndex::closest_other(const Ray& ray, Interval range, Found& found,
                                std::uint64_t* tests) const {
    return other_form([&](auto culled, auto hands_on) {
        return closest_in<decltype(culled)::value, decltype(hands_on)::value>(ray, range, found,
                                                                              tests);
    });
}

bool ObjectIndex::any_other(const Ray& ray, Interval range, Blocker* last,
                            std::uint64_t* tests) const {
    return other_form([&](auto culled, auto hands_on) {
        return any_in<decltype(culled)::value, decltype(hands_on)::value>(ray, range, last, tests);
    });
}

void Scene::build_index(int threads) {
    index = std::make_shared<const ObjectIndex>(objects, threads);
}

}  // namespace rt
