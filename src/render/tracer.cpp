#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "accel/object_index.h"
#include "render/primary_mask.h"
#include "rt/optics.h"
#include "rt/trace.h"

namespace rt {

double hit_tolerance(const Vec3& origin) { return kHitTolerance * (1 + max_abs_component(origin)); }

namespace {

// How a surface shares out the light it does not scatter: the weights of the highlight, of
// the reflected ray and of the refracted ray, and the refracted direction (none on total
// internal reflection, or where nothing is transmitted).
struct Split {
    double highlight;
    double mirror;
    double transmit;
    std::optional<Vec3> refracted;
};

// For a ray going from index n1 into n2 through a surface whose normal faces it.
Split split_light(const Material& m, const Vec3& incoming, const Vec3& facing, double n1, double n2,
                  bool refraction) {
    Split split{m.ks, m.ks, m.kt, std::nullopt};
    if (m.fresnel) {
        // A dielectric (114): F reflected, 1 - F transmitted; the highlight keeps ks. F is
        // needed for the mirror even when refraction is switched off.
        split.refracted = refract(incoming, facing, n1 / n2);
        split.mirror = split.refracted ? fresnel_reflectance(-dot(incoming, facing), n1, n2) : 1.0;
        split.transmit = 1 - split.mirror;
    } else if (m.kt > 0 && refraction) {
        split.refracted = refract(incoming, facing, n1 / n2);
        // On total internal reflection kt joins ks, for the highlight and the mirror alike.
        if (!split.refracted) {
            split.highlight += m.kt;
            split.mirror += m.kt;
        }
    }
    return split;
}

// The fraction of light left after travelling t through a medium of this absorption.
Spectrum transmittance(const Spectrum& absorption, double t) {
    Spectrum left;
    for (std::size_t i = 0; i < kSpectrumComponents; ++i) left[i] = std::exp(-absorption[i] * t);
    return left;
}

// A shading normal turned to the side the ray arrives on (as the face normal was, by
// `leaving`), and kept in the hemisphere the ray comes from: where it still faces away from
// the ray (near a coarse mesh's silhouette), it is reflected across the plane perpendicular
// to the ray, which is continuous where it grazes and leaves the rest alone. Without that, the
// mirror direction would point into the surface and the lights behind the viewer's horizon
// would shade the point: the black speckles of a coarse smooth mesh.
Vec3 visible_shading_normal(const Vec3& outward, bool leaving, const Vec3& direction) {
    const Vec3 s = leaving ? -outward : outward;
    const double toward = -dot(s, direction);
    if (!(toward < 0)) return s;
    return normalized(s + 2 * toward * direction);
}

// Where a switch over RenderMode meets a value outside it. Out of line, so that the code that
// builds the exception does not stand in the way of inlining its caller.
[[noreturn]] void not_a_render_mode() { throw std::logic_error("Tracer: not a render mode"); }

}  // namespace

Tracer::Tracer(const Scene& scene, const RenderOptions& options)
    : Tracer(scene, options, {0, 0, scene.viewer.xres, scene.viewer.yres}) {}

Tracer::Tracer(const Scene& scene, const RenderOptions& options, const PixelRect& area)
    : scene_(scene),
      index_(scene.index.get()),
      options_(options),
      escaped_(scene.background.value_or(scene.ambient)),
      plane_centre_(scene.viewer.plane_centre()),
      blocker_levels_(std::clamp(options.max_depth, 0, kBlockerLevels - 1) + 1),
      last_blockers_(kBlockerPadding +
                     static_cast<std::size_t>(blocker_levels_) * scene.lights.size() +
                     kBlockerPadding) {
    for (const Light& light : scene.lights)
        light_rows_.push_back({&light, light.point(), light.sample_count()});
    column_alphas_.resize(static_cast<std::size_t>(std::max(scene.viewer.xres, 0)));
    for (std::size_t x = 0; x < column_alphas_.size(); ++x)
        column_alphas_[x] = scene.viewer.alpha(static_cast<double>(x));
    if (options_.samples > 1) {
        const int n = options_.samples;
        for (int k = 0; k < n; ++k) grid_offsets_.push_back((k + 0.5) / n - 0.5);
        grid_alphas_.resize(static_cast<std::size_t>(n));
        grid_betas_.resize(static_cast<std::size_t>(n));
        grid_rays_.resize(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
    }
    // A backend replaces the hierarchy: it is asked on the path of the linear scan, so that
    // rt's own path (the hierarchy's) does not test for it on every ray.
    if (options_.queries != nullptr) options_.accelerate = false;
    if (options_.accelerate && (index_ == nullptr || !index_->covers(scene_.objects.size())))
        throw std::logic_error("Tracer: the scene's index was not built (Scene::build_index)");
    if (options_.accelerate && !area.empty()) {
        // One box for every 256 pixels rendered at most: the mask costs its boxes' projections
        // and the tiles they cover, a small part of the render however many objects there are.
        const std::size_t pixels =
            static_cast<std::size_t>(area.width()) * static_cast<std::size_t>(area.height());
        primary_mask_ = std::make_shared<const PrimaryMask>(
            scene.viewer, index_->outline(std::max<std::size_t>(pixels / 256, 8)), area);
        spares_blank_pixels_ = index_->unbounded_count() == 0;
    }
}

std::optional<SceneHit> Tracer::closest_hit(const Ray& ray, bool bounded) {
    Interval range{hit_tolerance(ray.origin), kInfinity};
    if (options_.accelerate) {
        ObjectIndex::Found found;
        if (!(bounded ? index_->closest(ray, range, found, &stats_.object_tests)
                      : index_->closest_unbounded(ray, range, found, &stats_.object_tests)))
            return std::nullopt;
        return SceneHit{&scene_.objects[found.object], found.hit};
    }
    if (options_.queries != nullptr) {
        SceneHit found{};
        if (!options_.queries->closest(ray, range, found)) return std::nullopt;
        return found;
    }
    // The linear scan: every object in file order.
    std::optional<SceneHit> best;
    stats_.object_tests += scene_.objects.size();
    for (const Object& object : scene_.objects) {
        Hit hit;
        if (object.shape.intersect(ray, range, hit)) {
            best = SceneHit{&object, hit};
            range.t_max = hit.t;  // later objects need only beat this
        }
    }
    return best;
}

bool Tracer::blocked(const Ray& ray, double distance) { return blocked(ray, distance, nullptr); }

bool Tracer::blocked(const Ray& ray, double distance, LastBlocker* last) {
    ++stats_.shadow_rays;
    const Interval range{hit_tolerance(ray.origin), distance};
    if (options_.accelerate) return index_->any(ray, range, last, &stats_.object_tests);
    if (options_.queries != nullptr) return options_.queries->any(ray, range);
    return std::any_of(scene_.objects.begin(), scene_.objects.end(), [&](const Object& o) {
        ++stats_.object_tests;
        return o.shape.intersect_any(ray, range);
    });
}

Spectrum Tracer::direct_light(const Vec3& point, const Vec3& facing_normal, const Vec3& shading,
                              const Vec3& reflected, const Material& m, double ks,
                              LastBlocker* blockers) {
    // Without a diffuse term (kd or the colour zero, or diffuse light off) only a highlight
    // can light the point, and where it is exactly zero the light adds nothing, blocked or
    // not: then no shadow ray is needed. A mirror's highlight is zero wherever the light
    // lies more than 90 degrees from the mirror direction, and one of exponent 1e5 (the
    // SPD's mirrors') wherever r.s is below 0.993. With a diffuse term the shadow ray comes
    // first, as always, so that a blocked one costs neither term.
    const bool diffuse = options_.diffuse && m.kd != 0 && !m.colour.is_black();
    if (light_rows_.size() >= kBatchFrom)
        return diffuse ? lights_at<true, true>(point, facing_normal, shading, reflected, m, ks,
                                               blockers)
                       : lights_at<false, true>(point, facing_normal, shading, reflected, m, ks,
                                                blockers);
    return diffuse
               ? lights_at<true, false>(point, facing_normal, shading, reflected, m, ks, blockers)
               : lights_at<false, false>(point, facing_normal, shading, reflected, m, ks, blockers);
}

template <bool Diffuse, bool Batched>
Spectrum Tracer::lights_at(const Vec3& point, const Vec3& facing_normal, const Vec3& shading,
                           const Vec3& reflected, const Material& m, double ks,
                           LastBlocker* blockers) {
    Spectrum total(0.0);
    // Batched: the point lights' samples first, with the same arithmetic, so the same values.
    // Left unconstructed until sampled, so that no hit zeroes eight samples first (0.4 % of
    // the SPD's tree's and lattice's instructions).
    union Slot {
        LightSample sample;
        Slot() {}
    };
    Slot batch[Batched ? kBatchedLights : 1];
    const std::size_t batched = Batched ? std::min(light_rows_.size(), kBatchedLights) : 0;
    for (std::size_t l = 0; l < batched; ++l)
        if (light_rows_[l].point != nullptr)
            std::construct_at(&batch[l].sample, sample_point_light(*light_rows_[l].point, point));
    for (std::size_t l = 0; l < light_rows_.size(); ++l) {
        const LightRow& light = light_rows_[l];
        for (int i = 0; i < light.samples; ++i) {
            const LightSample s = light.point == nullptr ? light.light->sample(point, i)
                                  : l < batched          ? batch[l].sample
                                                         : sample_point_light(*light.point, point);
            const double facing = dot(facing_normal, s.direction);
            // A light lights the point when the face and the shading normal both face it:
            // the face, so that no light leaks through a surface from behind; the shading
            // normal, so that its diffuse term is never negative. (Where they are the same
            // vector, as for every primitive but the smooth mesh, the two tests are one.)
            const double lambert = dot(shading, s.direction);
            if (!(facing > 0) || !(lambert > 0) || s.intensity.is_black()) continue;
            // The shadow test is written out in both places below: through a lambda or a
            // helper the compiler kept more in memory, and diffuse surfaces' lighting took
            // about 7 % more instructions (docs/performance.md).
            const Ray shadow_ray{point, s.direction};
            if (Diffuse && options_.shadows && blocked(shadow_ray, s.distance, &blockers[l]))
                continue;
            Spectrum term(0.0);
            if (options_.diffuse) term += m.colour * (m.kd * lambert);
            const double highlight = dot(reflected, s.direction);
            if (options_.specular && ks > 0 && highlight > 0 &&
                highlight_may_count(*std::min_element(term.c.begin(), term.c.end()), ks, highlight,
                                    m.ke))
                term += Spectrum(ks * std::pow(highlight, m.ke));
            const Spectrum lit = s.intensity * term;
            if (!Diffuse && (lit.is_black() ||
                             (options_.shadows && blocked(shadow_ray, s.distance, &blockers[l]))))
                continue;
            total += lit;
        }
    }
    return total;
}

Spectrum Tracer::trace(const Ray& ray, int depth, double weight, double ior,
                       const Spectrum& absorption) {
    if (depth == 0) ++stats_.primary_rays;  // secondary rays are counted where they start
    const auto found = closest_hit(ray);
    // A ray that escapes brings back the background (115), else the ambient intensity; inside
    // glass it is not attenuated (nothing was hit, so there is no distance to decay over).
    if (!found) return escaped_;
    return shade(ray, *found, depth, weight, ior, absorption);
}

// Inlined always, into trace and primary, as it was written inside trace before primary
// needed it too: as a call of its own it made the SPD's balls take 0.2 % more instructions
// (callgrind, 128 x 128).
[[gnu::always_inline]] inline Spectrum Tracer::shade(const Ray& ray, const SceneHit& found,
                                                     int depth, double weight, double ior,
                                                     const Spectrum& absorption) {
    const Object& object = *found.object;
    const Vec3 point = ray.at(found.hit.t);
    const Vec3 outward = object.shape.normal(point, found.hit);
    const bool leaving = dot(ray.direction, outward) > 0;
    const Vec3 facing = leaving ? -outward : outward;  // d in the Phong model
    // The geometric normal (the face's) decides the side; a smooth mesh shades with its own.
    const bool smooth = object.shape.has_shading_normal();
    const Vec3 shading =
        smooth ? visible_shading_normal(object.shape.shading_normal(point, found.hit, outward),
                                        leaving, ray.direction)
               : facing;
    const Material m = object.surface_at(found.hit).at(point);
    Spectrum result(0.0);

    // Transmission comes first: on total internal reflection its weight joins the mirror's.
    // The refracted ray enters the medium behind the surface, or leaving returns to air.
    const double next_ior = leaving ? 1.0 : m.ior;
    Split split = split_light(m, ray.direction, shading, ior, next_ior, options_.refraction);
    // A refracted ray must cross the face: where the shading normal would keep it on the near
    // side, the surface refracts about its face instead.
    if (smooth && split.refracted && !(dot(*split.refracted, facing) < 0))
        split = split_light(m, ray.direction, facing, ior, next_ior, options_.refraction);
    const double kt = split.transmit;
    if (split.refracted && kt > 0 && options_.refraction && may_trace(depth + 1, weight * kt)) {
        ++stats_.refracted_rays;
        result += kt * trace({point, *split.refracted}, depth + 1, weight * kt, next_ior,
                             leaving ? Spectrum(0.0) : m.absorption);
    }

    if (options_.ambient) result += scene_.ambient * m.colour * m.kd;
    Vec3 reflected = reflect(ray.direction, shading);
    // A mirrored ray must leave the face: where the shading normal would send it into the
    // surface, the surface mirrors about its face instead.
    if (smooth && !(dot(reflected, facing) > 0)) reflected = reflect(ray.direction, facing);
    if (options_.diffuse || options_.specular)
        result +=
            direct_light(point, facing, shading, reflected, m, split.highlight, blockers_at(depth));
    // The reflected ray stays in the medium it came through.
    const double ks = split.mirror;
    if (ks > 0 && options_.reflection && may_trace(depth + 1, weight * ks)) {
        ++stats_.reflected_rays;
        result += ks * trace({point, reflected}, depth + 1, weight * ks, ior, absorption);
    }
    // Light from this hit crossed the medium for found.hit.t on its way back.
    if (!absorption.is_black()) result *= transmittance(absorption, found.hit.t);
    return result;
}

Spectrum Tracer::shade_primary(const Ray& ray) { return primary(ray, true); }

std::size_t Tracer::row_rays(int y, int x0, int x1, std::vector<Ray>& rays,
                             std::vector<unsigned char>& spared) const {
    const auto width = static_cast<std::size_t>(x1 - x0);
    rays.resize(width);
    spared.assign(width, 0);
    std::size_t count = 0;
    if (spares_blank_pixels_)
        for (std::size_t i = 0; i < width; ++i)
            if (!primary_mask_->may_hit(x0 + static_cast<int>(i), y)) {
                spared[i] = 1;
                ++count;
            }
    const Viewer& viewer = scene_.viewer;
    const double beta = viewer.beta(y);
    for (std::size_t i = 0; i < width; ++i)
        if (spared[i] == 0)
            rays[i] = viewer.ray_through(column_alphas_[static_cast<std::size_t>(x0) + i], beta,
                                         plane_centre_);
    return count;
}

Spectrum Tracer::shade_pixel_ray(const Ray& ray, int x, int y) {
    return primary(ray, primary_mask_ == nullptr || primary_mask_->may_hit(x, y));
}

Spectrum Tracer::primary(const Ray& ray, bool bounded) {
    ++stats_.primary_rays;
    const auto found = closest_hit(ray, bounded);
    // The trace mode as trace() at depth 0.
    if (options_.mode == RenderMode::trace)
        return found ? shade(ray, *found, 0, 1, 1, Spectrum(0.0)) : escaped_;
    // The other modes show one property of the first hit, and black where the ray escapes.
    if (!found) return Spectrum(0.0);
    const Vec3 point = ray.at(found->hit.t);
    switch (options_.mode) {
        case RenderMode::depth:
            return Spectrum(std::min(1.0, 1 / found->hit.t));
        case RenderMode::colour:
            return found->object->surface_at(found->hit).at(point).colour;
        case RenderMode::normal: {
            const Vec3 n = found->object->shape.shading_normal(point, found->hit);
            return Spectrum(std::fabs(dot(n, ray.direction)));
        }
        case RenderMode::trace:  // traced above
            break;
    }
    not_a_render_mode();
}

Spectrum Tracer::pixel(int x, int y, const Spectrum* traced_centre) {
    const int n = options_.samples;
    if (n <= 1) return traced_centre != nullptr ? *traced_centre : one_ray(x, y);
    // An n x n grid centred on the original's ray (offsets (k + 1/2)/n - 1/2), so that every n
    // renders the same geometry. For odd n the middle offset is exactly 0: that sample is the
    // original's ray itself, and a value already traced for it can stand in, bit for bit.
    const int middle = n % 2 == 1 ? n / 2 : -1;
    const bool bounded = primary_mask_ == nullptr || primary_mask_->may_hit(x, y);
    // Rays that surely meet nothing (as in row_rays) are not made: each is the background.
    const bool blank = spares_blank_pixels_ && !bounded;
    const auto size = static_cast<std::size_t>(n);
    if (!blank) {
        // The grid's n alphas and n betas, then its rays, before any is traced: each the
        // double primary_ray(x + u, y + v) computes, with two divisions a pixel's row or
        // column of samples instead of two a sample, and the rays' square roots and divisions
        // overlapping rather than each waiting ahead of its trace.
        const Viewer& viewer = scene_.viewer;
        for (std::size_t k = 0; k < size; ++k) {
            grid_alphas_[k] = viewer.alpha(x + grid_offsets_[k]);
            grid_betas_[k] = viewer.beta(y + grid_offsets_[k]);
        }
        for (std::size_t j = 0; j < size; ++j)
            for (std::size_t i = 0; i < size; ++i)
                grid_rays_[j * size + i] =
                    viewer.ray_through(grid_alphas_[i], grid_betas_[j], plane_centre_);
    }
    Spectrum sum(0.0);
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            if (traced_centre != nullptr && i == middle && j == middle) {
                sum += *traced_centre;
                continue;
            }
            if (blank) {
                count_blank_pixels(1);
                sum += blank_pixel();
                continue;
            }
            sum += primary(
                grid_rays_[static_cast<std::size_t>(j) * size + static_cast<std::size_t>(i)],
                bounded);
        }
    }
    return sum * (1.0 / (n * n));
}

}  // namespace rt
