// The recursive tracer of sections 1.6 to 1.10 of the original: what one ray brings back.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "rt/options.h"
#include "rt/raster.h"
#include "rt/scene.h"

namespace rt {

// Hits nearer than this, relative to the size of the ray origin's coordinates, are rejected,
// so that a ray leaving a surface does not find that surface again at its own origin
// (the "trapped rays" of section 1.10.1).
inline constexpr double kHitTolerance = 1e-7;

// The smallest distance a hit along a ray from `origin` may have.
double hit_tolerance(const Vec3& origin);

struct SceneHit {
    const Object* object;
    Hit hit;
};

class PrimaryMask;

// What answers a tracer's two ray queries when RenderOptions::queries is set, in place of the
// scene's hierarchy or the linear scan. Every render thread calls it at once: it must be
// thread-safe. The tracer's object_tests do not count its tests.
class RayQueries {
  public:
    virtual ~RayQueries() = default;
    // The nearest hit with range.t_min < t < range.t_max, as the linear scan defines it (of
    // objects hit at the same distance, the earliest in the scene's list).
    virtual bool closest(const Ray& ray, Interval range, SceneHit& found) const = 0;
    // Whether any object lies along the ray in range.
    virtual bool any(const Ray& ray, Interval range) const = 0;
};

// How many rays of each kind a render traced, and how many times an object was asked whether
// a ray hits it (a mesh counts once, however many of its triangles it tests).
struct RenderStats {
    std::uint64_t primary_rays = 0;
    std::uint64_t reflected_rays = 0;
    std::uint64_t refracted_rays = 0;
    std::uint64_t shadow_rays = 0;
    std::uint64_t object_tests = 0;

    std::uint64_t secondary_rays() const { return reflected_rays + refracted_rays; }
    std::uint64_t total() const { return primary_rays + secondary_rays() + shadow_rays; }
    RenderStats& operator+=(const RenderStats& other) {
        primary_rays += other.primary_rays;
        reflected_rays += other.reflected_rays;
        refracted_rays += other.refracted_rays;
        shadow_rays += other.shadow_rays;
        object_tests += other.object_tests;
        return *this;
    }
};

// Traces rays through a scene. A Tracer counts the rays it traces and remembers the last
// blocker of each light at each level of the ray tree, so tracing changes it and each thread
// uses its own; the scene is shared read-only. With options.accelerate (the default) the scene's
// index must have been built (read_scene does), or construction throws std::logic_error;
// with options.queries it is not used, nor needed.
// Aligned to a cache line, and its per-light blockers kept a line away from the ends of their
// allocation: the tracers of a render's threads lie side by side, each writes its counters
// and blockers on almost every ray, and a line two threads write would pass between their
// cores on every write (false sharing).
class alignas(64) Tracer {
  public:
    Tracer(const Scene& scene, const RenderOptions& options);
    // The same for rendering the pixels of `area` alone (a region of the image, with -a's
    // margin): the primary mask is made for them only.
    Tracer(const Scene& scene, const RenderOptions& options, const PixelRect& area);

    // The light arriving back along a ray; depth and weight as the contract's recursion rules,
    // ior and absorption those of the medium the ray travels in: what the ray brings back from
    // a hit at distance t is multiplied by exp(-absorption t).
    Spectrum trace(const Ray& ray, int depth = 0, double weight = 1, double ior = 1,
                   const Spectrum& absorption = Spectrum(0.0));
    // A primary ray's value in the current render mode.
    Spectrum shade_primary(const Ray& ray);
    // The same for a ray from the eye through pixel (x, y) of the image: the original's, or
    // one of its grid's (within half a pixel of it). Where no bounded object can lie along
    // such rays (PrimaryMask), the hierarchy is not walked; the value is the same.
    Spectrum shade_pixel_ray(const Ray& ray, int x, int y);
    // The value of pixel (x, y): the mean of options.samples^2 primary rays on a grid centred
    // on the original's ray through (x, y). traced_centre, when given, is that ray's value,
    // already traced: an odd grid, whose middle sample is that ray, uses it instead of
    // tracing the ray again (the sum is the same, bit for bit).
    Spectrum pixel(int x, int y, const Spectrum* traced_centre = nullptr);
    // The value of the original's one ray through pixel (x, y), whatever options.samples is.
    Spectrum one_ray(int x, int y) { return shade_pixel_ray(primary_ray(x, y), x, y); }
    // The original's one ray through pixel (x, y), and those of columns x0 to x1 - 1 of row
    // y into `rays`, made one after another before any is traced: their square roots and
    // divisions then overlap, where each would otherwise wait ahead of its trace.
    Ray primary_ray(int x, int y) const { return scene_.viewer.primary_ray(x, y, plane_centre_); }
    // The columns' alphas come from a table, each the same double primary_ray computes: a
    // division less per ray, where the square root and the division that normalise it
    // already keep the divider busy.
    // A pixel whose ray surely meets nothing (no bounded object's box on it, by the primary
    // mask, and no unbounded object in the scene) gets no ray: `spared` marks it with 1, and
    // its value is blank_pixel(). Returns how many were spared.
    std::size_t row_rays(int y, int x0, int x1, std::vector<Ray>& rays,
                         std::vector<unsigned char>& spared) const;
    // A spared pixel's value: what a primary ray that hits nothing brings back in the render
    // mode. count_blank_pixels counts them as the primary rays they stand for.
    Spectrum blank_pixel() const {
        return options_.mode == RenderMode::trace ? escaped_ : Spectrum(0.0);
    }
    void count_blank_pixels(std::size_t count) { stats_.primary_rays += count; }

    // The nearest hit; with `bounded` false, among the unbounded objects only (for a ray
    // the primary mask says crosses no bounded object's box).
    std::optional<SceneHit> closest_hit(const Ray& ray, bool bounded = true);
    // True when any object lies along the ray closer than `distance`.
    bool blocked(const Ray& ray, double distance);

    const RenderStats& stats() const { return stats_; }

  private:
    // shade_primary, the hierarchy asked or not.
    Spectrum primary(const Ray& ray, bool bounded);
    // What a ray brings back from its nearest hit (trace's arguments).
    Spectrum shade(const Ray& ray, const SceneHit& found, int depth, double weight, double ior,
                   const Spectrum& absorption);
    bool blocked(const Ray& ray, double distance, LastBlocker* last);
    // facing_normal: the geometric normal turned to the ray; shading: the shading normal, the
    // same side (the same vector but for a smooth mesh).
    // blockers: the last blockers of the hit's level in the ray tree, one per light.
    Spectrum direct_light(const Vec3& point, const Vec3& facing_normal, const Vec3& shading,
                          const Vec3& reflected, const Material& m, double ks,
                          LastBlocker* blockers);
    // direct_light for a surface with a diffuse term (Diffuse) or without one; Batched
    // samples the point lights (up to kBatchedLights of them) before the loop over the lights.
    template <bool Diffuse, bool Batched>
    Spectrum lights_at(const Vec3& point, const Vec3& facing_normal, const Vec3& shading,
                       const Vec3& reflected, const Material& m, double ks, LastBlocker* blockers);
    bool may_trace(int depth, double weight) const {
        return depth <= options_.max_depth && weight >= options_.min_weight;
    }

    const Scene& scene_;
    const ObjectIndex* index_;  // the scene's hierarchy, when options_.accelerate
    RenderOptions options_;     // a copy: small, and safe when built from a temporary
    RenderStats stats_;
    Spectrum escaped_;                   // what a traced ray that hits nothing brings back
    Vec3 plane_centre_;                  // the viewer's, which every primary ray shares
    std::vector<double> column_alphas_;  // viewer.alpha(x) for each column x of the image
    // pixel()'s grid: the offsets (k + 1/2)/n - 1/2 of options.samples = n, and room for a
    // pixel's alphas, betas and rays, made before any is traced.
    std::vector<double> grid_offsets_, grid_alphas_, grid_betas_;
    std::vector<Ray> grid_rays_;
    // Per light of the scene, looked up once: its sample count and, for a point light, its
    // parameters, which the light loop samples inline (sample_point_light) rather than
    // through the light table (the SPD's tree, seven point lights: 0.94 of the time).
    struct LightRow {
        const Light* light;
        const PointLight* point;  // nullptr: not a point light
        int samples;
    };
    std::vector<LightRow> light_rows_;
    // With this many lights or more, the point lights are all sampled first and the shadow
    // rays cast after: the samples' square roots and divisions then overlap rather than each
    // waiting for the walk before it (the SPD's tree, seven lights: 0.91 of the time). With
    // fewer it did not pay for its stores (docs/performance.md, "Point lights sampled first").
    static constexpr std::size_t kBatchFrom = 4;
    static constexpr std::size_t kBatchedLights = 8;
    // Which pixels' primary rays may meet a bounded object; shared by the copies a render
    // makes for its threads (read-only). Empty without the hierarchy.
    std::shared_ptr<const PrimaryMask> primary_mask_;
    // Whether a pixel the mask leaves unmarked meets nothing at all, so that it needs no ray
    // (row_rays, pixel): there is a mask, and no unbounded object (a plane) to ask instead.
    bool spares_blank_pixels_ = false;
    // Per level of the ray tree and per light, the object that last blocked a shadow ray
    // toward it (Haines's shadow cache): a row of lights() for each of blocker_levels_
    // levels, from kBlockerPadding on; the levels from kBlockerLevels - 1 on share the last
    // row. Kept per level because consecutive hits at one level lie near each other (the
    // next pixel's), while a pixel's own levels do not: one row for all levels, which the
    // primary and the reflected hits took in turns, found the blocker first less often (the
    // SPD's gears took 0.91 of the time with the rows, lattice 0.94; docs/performance.md).
    static constexpr int kBlockerLevels = 8;
    static constexpr std::size_t kBlockerPadding = 64 / sizeof(LastBlocker);
    int blocker_levels_ = 1;
    std::vector<LastBlocker> last_blockers_;
    LastBlocker* blockers_at(int depth) {
        const auto level = static_cast<std::size_t>(std::min(depth, blocker_levels_ - 1));
        return &last_blockers_[kBlockerPadding + level * scene_.lights.size()];
    }
};

}  // namespace rt
