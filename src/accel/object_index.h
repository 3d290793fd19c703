// The hierarchy over a scene's objects: what the tracer asks for the nearest hit along a ray
// and for any blocker of a shadow ray, instead of testing every object in turn.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "accel/bvh.h"
#include "accel/parallel.h"
#include "accel/sphere_cull.h"
#include "rt/primitive.h"
#include "rt/scene.h"

namespace rt {

class ObjectIndex {
  public:
    // The nearest hit and the object's place in the scene's list.
    struct Found {
        std::uint32_t object;
        Hit hit;
    };

    using Blocker = LastBlocker;

    ObjectIndex() = default;
    // Objects with finite bounds go into the hierarchy; the rest (planes, and affines of
    // them) stay in a short list tested on every ray.
    explicit ObjectIndex(std::span<const Object> objects, int threads = 1);

    // Whether this index was built over exactly `count` objects.
    bool covers(std::size_t count) const { return object_count_ == count; }
    // Whether the hierarchy's spheres are culled eight at a time (SphereCull).
    bool culls_spheres() const { return !cull_.empty(); }
    std::size_t bounded_count() const { return bounded_count_; }
    // Whether the walk hands the ray it prepared on to the objects that take it (a mesh
    // among other objects: Entry::prepared).
    bool hands_on_ray() const { return (queries_ & kHandsOn) != 0; }
    std::size_t unbounded_count() const { return entries_.size() - bounded_count_; }

    // The nearest hit in range, exactly as testing every object in file order finds it: the
    // smallest distance, and of objects hit at the same distance, the one earliest in the
    // file.
    // With `tests`, the number of objects asked is added to it.
    bool closest(const Ray& ray, Interval range, Found& found,
                 std::uint64_t* tests = nullptr) const {
        // The plain query first: most scenes' (and the one test of a byte), the rest out of
        // line.
        if (queries_ == kPlain) return closest_in<false, false>(ray, range, found, tests);
        return closest_other(ray, range, found, tests);
    }
    // The same for a ray that crosses none of outline()'s boxes, so that no bounded object
    // can be hit: only the unbounded ones are asked.
    bool closest_unbounded(const Ray& ray, Interval range, Found& found,
                           std::uint64_t* tests = nullptr) const {
        return closest_in<false, false>(ray, range, found, tests, false);
    }
    // Boxes that together hold every bounded object (Bvh::outline), at most `at_most` of
    // them (but at least the root's children); none where there is no bounded object.
    // A lone object with a hierarchy of its own gives its own (Shape::own_hierarchy).
    std::vector<Bounds> outline(std::size_t at_most) const {
        return lone_hierarchy() ? lone_outline_(entries_[0].test.call.data, at_most)
                                : bvh_.outline(at_most);
    }
    // Whether any object is hit in range. With `last`, its object is tried first, and it
    // is set to the blocker found; where nothing blocks, it is forgotten unless it is a
    // sphere. A light's shadow rays pass in long runs where they pass at all, and each
    // would ask the forgotten blocker first, in vain: a cone or a cylinder costs several
    // times a sphere, which is kept, since a walk that finds it again costs more than its
    // test (the SPD's tree, cones lit by seven lights, took 0.88 of the time; forgetting
    // spheres as well took the SPD's balls 1.00 and mirror-49 1.02 for 22 % and 4 % fewer
    // tests; docs/performance.md).
    bool any(const Ray& ray, Interval range, Blocker* last = nullptr,
             std::uint64_t* tests = nullptr) const {
        const bool blocked = queries_ == kPlain ? any_in<false, false>(ray, range, last, tests)
                                                : any_other(ray, range, last, tests);
        if (!blocked && last != nullptr && last->entry < entries_.size() &&
            !entries_[last->entry].sphere)
            last->entry = kNone;
        return blocked;
    }

  private:
    // No entry, and no object: the largest 32-bit number, which indexes neither.
    static constexpr std::uint32_t kNone = LastBlocker{}.entry;

    // What a test needs, stored contiguously in the order the leaves visit them: 40 bytes,
    // one record per object wherever it is tested from.
    struct Entry {
        // A sphere's centre and squared radius, tested inline (its table row's sphere column)
        // without a call and without a load from anywhere else; any other object's functions
        // and parameters, tested through the table.
        union Test {
            struct Call {
                IntersectFn* intersect;
                IntersectFn* intersect_any;  // for shadow rays (Shape::any_hit_function)
                const void* data;
            } call;
            // For an object with a hierarchy of its own (a mesh), its functions that walk it
            // with the ray this walk prepared (PrimitiveFunctions::intersect_prepared).
            struct PreparedCall {
                PreparedIntersectFn* intersect;
                PreparedIntersectFn* intersect_any;
                const void* data;
            } prepared_call;
            double sphere[4];  // the centre's x, y and z, then the squared radius
        } test;
        std::uint32_t object;
        bool sphere;  // which of test's three is there: the sphere,
        // the prepared call (only in an index that hands its walk's ray on, whose queries
        // all make it: hands_on_ray()), or else the call
        bool prepared;
        // One test searches many parts (Shape::many_parts: a mesh, CSG, or a frame of one).
        bool many_parts;

        SphereParameters sphere_parameters() const {
            return {{test.sphere[0], test.sphere[1], test.sphere[2]}, test.sphere[3]};
        }
    };
    static_assert(sizeof(Entry) == 40);

    // The leaves that cull their spheres (SphereCull) hold at least this many objects;
    // smaller ones test theirs one by one.
    static constexpr std::uint32_t kCulledLeaf = 4;
    static_assert(Bvh::kMaxLeafSize <= SphereCull::kLanes);  // a leaf is one vector test

    // The cull is built where a ray through the hierarchy asks, by the SAH's measure, at
    // least this many spheres of such leaves: where spheres overlap heavily (the bench's
    // shells-250 asks 31, shells-4000 319). Elsewhere its cost is not repaid: mirror-49 (4
    // spheres) took 1.10 of the time with it, spheres-10k (2) 1.03.
    static constexpr double kCulledTests = 16;

    // With hands_on, the object's prepared call where its row has one (Entry::prepared).
    static Entry entry(const Object& object, std::uint32_t index, bool hands_on);
    // Whether a ray through the hierarchy asks at least kCulledTests spheres of its leaves
    // of kCulledLeaf objects or more (each such leaf's area over the root's, times its
    // spheres).
    bool cull_pays() const;
    // Culled: with cull_. HandsOn: the walk's prepared ray is handed on to the entries that
    // take it (hands_on_ray()).
    template <bool Culled, bool HandsOn>
    bool closest_in(const Ray& ray, Interval range, Found& found, std::uint64_t* tests,
                    bool bounded = true) const;
    template <bool Culled, bool HandsOn>
    bool any_in(const Ray& ray, Interval range, Blocker* last, std::uint64_t* tests) const;
    // closest_in and any_in for an index whose queries are not plain: other_form calls
    // query(culled, hands_on), two std::bool_constant, for the form queries_ names.
    template <class Query>
    bool other_form(const Query& query) const;
    bool closest_other(const Ray& ray, Interval range, Found& found, std::uint64_t* tests) const;
    bool any_other(const Ray& ray, Interval range, Blocker* last, std::uint64_t* tests) const;
    // Whether entry i is hit in range (hit as intersect leaves it). `walked`: the ray as the
    // walk prepared it, WideRay(ray, range.t_min), or nullptr; given to a prepared call.
    template <bool HandsOn>
    bool hits(std::uint32_t i, const Ray& ray, Interval range, Hit& hit,
              const WideRay* walked) const;
    template <bool HandsOn>
    bool blocks(std::uint32_t i, const Ray& ray, Interval range, Hit& scratch,
                const WideRay* walked) const;

    Bvh bvh_;
    // The bounded objects in leaf order, then the unbounded ones in file order. Allocated
    // without being written first, so that the threads filling it touch its pages.
    std::vector<Entry, UninitializedAllocator<Entry>> entries_;
    std::size_t bounded_count_ = 0;
    std::size_t object_count_ = 0;
    // Where the one bounded object has a hierarchy of its own (Shape::own_hierarchy: a
    // model, alone or on a floor), that object's outline column; nullptr elsewhere. Such an
    // object is asked directly, since its own walk turns away a ray outside its box about as
    // fast as this one's would, and the walk here cost the SPD's nurbtst 9 % of its
    // instructions (docs/performance.md, "A lone mesh asked directly").
    OutlineFn* lone_outline_ = nullptr;
    bool lone_hierarchy() const { return lone_outline_ != nullptr; }
    // Where cull_pays(): the spheres, culled eight at a time before their exact tests (in
    // scenes of spheres that overlap heavily, which the hierarchy cannot part, the render
    // took 0.73-0.94 of the time, the more overlap the less). Empty elsewhere.
    SphereCull cull_;
    // Which closest_in and any_in the queries call: kCulled where the spheres are culled
    // (culls_spheres), kHandsOn where an entry of the hierarchy takes the walk's prepared ray
    // (Entry::prepared: a mesh among other objects); elsewhere the walk is not asked for it.
    // One flag for both, read once per query.
    static constexpr std::uint8_t kPlain = 0, kCulled = 1, kHandsOn = 2;
    std::uint8_t queries_ = kPlain;
};

}  // namespace rt
