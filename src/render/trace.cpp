#include "rt/trace.h"

#include "accel/object_index.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <thread>
#include <vector>

namespace rt {

double hit_tolerance(const Vec3& origin) { return kHitTolerance * (1 + max_abs_component(origin)); }

Vec3 reflect(const Vec3& incoming, const Vec3& normal) {
    return incoming - 2 * dot(incoming, normal) * normal;
}

std::optional<Vec3> refract(const Vec3& incoming, const Vec3& normal, double eta) {
    const double cos_i = -dot(incoming, normal);
    const double k = 1 - eta * eta * (1 - cos_i * cos_i);
    if (k < 0) return std::nullopt;
    return normalized(eta * incoming + (eta * cos_i - std::sqrt(k)) * normal);
}

double fresnel_reflectance(double cos_i, double n1, double n2) {
    cos_i = std::clamp(cos_i, 0.0, 1.0);
    const double eta = n1 / n2;
    const double sin2_t = eta * eta * (1 - cos_i * cos_i);  // Snell's law, squared
    if (sin2_t >= 1) return 1;                              // total internal reflection
    const double cos_t = std::sqrt(1 - sin2_t);
    const double s = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    const double p = (n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i);
    return (s * s + p * p) / 2;
}

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

}  // namespace

Tracer::Tracer(const Scene& scene, const RenderOptions& options)
    : scene_(scene), index_(scene.index.get()), options_(options),
      last_blockers_(scene.lights.size()) {
    if (options_.accelerate && (index_ == nullptr || !index_->covers(scene_.objects.size())))
        throw std::logic_error("Tracer: the scene's index was not built (Scene::build_index)");
}

std::optional<SceneHit> Tracer::closest_hit(const Ray& ray) const {
    Interval range{hit_tolerance(ray.origin), kInfinity};
    if (options_.accelerate) {
        ObjectIndex::Found found;
        if (!index_->closest(ray, range, found, &stats_.object_tests)) return std::nullopt;
        return SceneHit{&scene_.objects[found.object], found.hit};
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

bool Tracer::blocked(const Ray& ray, double distance) const {
    return blocked(ray, distance, nullptr);
}

bool Tracer::blocked(const Ray& ray, double distance, LastBlocker* last) const {
    ++stats_.shadow_rays;
    const Interval range{hit_tolerance(ray.origin), distance};
    if (options_.accelerate) return index_->any(ray, range, last, &stats_.object_tests);
    return std::any_of(scene_.objects.begin(), scene_.objects.end(), [&](const Object& o) {
        ++stats_.object_tests;
        return o.shape.intersect_any(ray, range);
    });
}

Spectrum Tracer::direct_light(const Vec3& point, const Vec3& facing_normal, const Vec3& reflected,
                              const Material& m, double ks) const {
    Spectrum total(0.0);
    for (std::size_t l = 0; l < scene_.lights.size(); ++l) {
        const Light& light = scene_.lights[l];
        const int samples = light.sample_count();
        for (int i = 0; i < samples; ++i) {
            const LightSample s = light.sample(point, i);
            const double facing = dot(facing_normal, s.direction);
            if (!(facing > 0) || s.intensity.is_black()) continue;
            if (options_.shadows && blocked({point, s.direction}, s.distance, &last_blockers_[l]))
                continue;
            Spectrum term(0.0);
            if (options_.diffuse) term += m.colour * (m.kd * facing);
            const double highlight = dot(reflected, s.direction);
            if (options_.specular && ks > 0 && highlight > 0)
                term += Spectrum(ks * std::pow(highlight, m.ke));
            total += s.intensity * term;
        }
    }
    return total;
}

Spectrum Tracer::trace(const Ray& ray, int depth, double weight, double ior,
                       const Spectrum& absorption) const {
    if (depth == 0) ++stats_.primary_rays;  // secondary rays are counted where they start
    const auto found = closest_hit(ray);
    // A ray that escapes brings back the ambient intensity.
    if (!found) return scene_.ambient;

    const Object& object = *found->object;
    const Vec3 point = ray.at(found->hit.t);
    const Vec3 outward = object.shape.normal(point, found->hit);
    const bool leaving = dot(ray.direction, outward) > 0;
    const Vec3 facing = leaving ? -outward : outward;  // d in the Phong model
    const Material m = object.surface_at(found->hit).at(point);
    Spectrum result(0.0);

    // Transmission comes first: on total internal reflection its weight joins the mirror's.
    // The refracted ray enters the medium behind the surface, or leaving returns to air.
    const double next_ior = leaving ? 1.0 : m.ior;
    const Split split = split_light(m, ray.direction, facing, ior, next_ior, options_.refraction);
    const double kt = split.transmit;
    if (split.refracted && kt > 0 && options_.refraction && may_trace(depth + 1, weight * kt)) {
        ++stats_.refracted_rays;
        result += kt * trace({point, *split.refracted}, depth + 1, weight * kt, next_ior,
                             leaving ? Spectrum(0.0) : m.absorption);
    }

    if (options_.ambient) result += scene_.ambient * m.colour * m.kd;
    const Vec3 reflected = reflect(ray.direction, facing);
    if (options_.diffuse || options_.specular)
        result += direct_light(point, facing, reflected, m, split.highlight);
    // The reflected ray stays in the medium it came through.
    const double ks = split.mirror;
    if (ks > 0 && options_.reflection && may_trace(depth + 1, weight * ks)) {
        ++stats_.reflected_rays;
        result += ks * trace({point, reflected}, depth + 1, weight * ks, ior, absorption);
    }
    // Light from this hit crossed the medium for found->hit.t on its way back.
    if (!absorption.is_black()) result *= transmittance(absorption, found->hit.t);
    return result;
}

Spectrum Tracer::shade_primary(const Ray& ray) const {
    if (options_.mode == RenderMode::trace) return trace(ray);
    ++stats_.primary_rays;
    const auto found = closest_hit(ray);
    if (!found) return Spectrum(0.0);
    const Vec3 point = ray.at(found->hit.t);
    switch (options_.mode) {
        case RenderMode::depth:
            return Spectrum(std::min(1.0, 1 / found->hit.t));
        case RenderMode::colour:
            return found->object->surface_at(found->hit).at(point).colour;
        case RenderMode::normal: {
            const Vec3 n = found->object->shape.normal(point, found->hit);
            return Spectrum(std::fabs(dot(n, ray.direction)));
        }
        case RenderMode::trace:
            break;
    }
    return trace(ray);
}

Spectrum Tracer::pixel(int x, int y, const Spectrum* traced_centre) const {
    const int n = options_.samples;
    if (n <= 1) return traced_centre != nullptr ? *traced_centre : one_ray(x, y);
    // An n x n grid centred on the original's ray (offsets (k + 1/2)/n - 1/2), so that every n
    // renders the same geometry. For odd n the middle offset is exactly 0: that sample is the
    // original's ray itself, and a value already traced for it can stand in, bit for bit.
    const int middle = n % 2 == 1 ? n / 2 : -1;
    Spectrum sum(0.0);
    for (int j = 0; j < n; ++j) {
        const double v = (j + 0.5) / n - 0.5;
        for (int i = 0; i < n; ++i) {
            if (traced_centre != nullptr && i == middle && j == middle) {
                sum += *traced_centre;
                continue;
            }
            const double u = (i + 0.5) / n - 0.5;
            sum += shade_primary(scene_.viewer.primary_ray(x + u, y + v));
        }
    }
    return sum * (1.0 / (n * n));
}

int worker_threads(int requested) {
    if (requested > 0) return requested;
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

namespace {

// This rectangle grown by one pixel on every side, but kept within `bounds`.
PixelRect with_margin(const PixelRect& r, const PixelRect& bounds) {
    return {std::max(r.x0 - 1, bounds.x0), std::max(r.y0 - 1, bounds.y0),
            std::min(r.x1 + 1, bounds.x1), std::min(r.y1 + 1, bounds.y1)};
}

// A raster that holds the pixels of `rect` only, addressed by full-image coordinates: a
// region's pixels are computed at their own (x, y), so they are the whole render's pixels.
class Window {
  public:
    explicit Window(const PixelRect& rect) : rect_(rect), raster_(rect.width(), rect.height()) {}
    Spectrum at(int x, int y) const { return raster_.at(x - rect_.x0, y - rect_.y0); }
    void set(int x, int y, const Spectrum& s) { raster_.set(x - rect_.x0, y - rect_.y0, s); }
    // The pixels of `part` (within this window) as a raster of their own.
    Raster crop(const PixelRect& part) const {
        if (part == rect_) return raster_;
        Raster out(part.width(), part.height());
        for (int y = part.y0; y < part.y1; ++y)
            for (int x = part.x0; x < part.x1; ++x) out.set(x - part.x0, y - part.y0, at(x, y));
        return out;
    }

  private:
    PixelRect rect_;
    Raster raster_;
};

// Calls work(tracer, y) for every row y of `rect`, rows shared among the tracers' threads
// (one thread per tracer); returns once every row is done.
// With `progress`, each finished row and the rays traced for it are published.
template <typename Work>
void for_each_row(const std::vector<Tracer>& tracers, const PixelRect& rect, const Work& work,
                  RenderProgress* progress = nullptr) {
    std::atomic<int> next_row{rect.y0};
    auto worker = [&](const Tracer& tracer) {
        std::uint64_t published = tracer.stats().total();
        for (int y = next_row++; y < rect.y1; y = next_row++) {
            work(tracer, y);
            if (progress == nullptr) continue;
            const std::uint64_t traced = tracer.stats().total();
            progress->rays.fetch_add(traced - published, std::memory_order_relaxed);
            progress->rows_done.fetch_add(1, std::memory_order_relaxed);
            published = traced;
        }
    };
    std::vector<std::jthread> pool;
    for (std::size_t i = 1; i < tracers.size(); ++i)
        pool.emplace_back(worker, std::cref(tracers[i]));
    worker(tracers[0]);
}  // every worker joins here

// Whether one-ray values a and b differ by more than `threshold` in some component, compared
// as the image will be written: clamped to [0, 1].
bool differ(const Spectrum& a, const Spectrum& b, double threshold) {
    for (std::size_t i = 0; i < kSpectrumComponents; ++i)
        if (std::fabs(std::clamp(a[i], 0.0, 1.0) - std::clamp(b[i], 0.0, 1.0)) > threshold)
            return true;
    return false;
}

// Whether pixel (x, y) differs from one of its 4-connected neighbours within `known`, the
// pixels whose one-ray values `one_ray` holds.
bool needs_supersampling(const Window& one_ray, const PixelRect& known, int x, int y,
                         double threshold) {
    const Spectrum here = one_ray.at(x, y);
    return (x > known.x0 && differ(here, one_ray.at(x - 1, y), threshold)) ||
           (x + 1 < known.x1 && differ(here, one_ray.at(x + 1, y), threshold)) ||
           (y > known.y0 && differ(here, one_ray.at(x, y - 1), threshold)) ||
           (y + 1 < known.y1 && differ(here, one_ray.at(x, y + 1), threshold));
}

// Adaptive supersampling of `rect` into `raster`. The decisions are taken from one-ray values
// only, never from what a thread has seen, so the image is the same on any number of threads.
// They need the one-ray values of a one-pixel margin around `rect` (within the image), which
// `raster` must cover: a region of the image rendered this way decides at its edges exactly
// as the whole image does.
void render_adaptive(const std::vector<Tracer>& tracers, const PixelRect& rect,
                     const PixelRect& image, double threshold, Window& raster,
                     RenderProgress* progress) {
    const PixelRect known = with_margin(rect, image);
    // The one-ray pass and the grid pass trace; deciding is quick and not counted.
    if (progress != nullptr)
        progress->rows_total.store(
            static_cast<std::uint64_t>((known.y1 - known.y0) + rect.height()));
    for_each_row(
        tracers, known,
        [&](const Tracer& tracer, int y) {
            for (int x = known.x0; x < known.x1; ++x) raster.set(x, y, tracer.one_ray(x, y));
        },
        progress);
    // Decided for the whole rectangle before any pixel is overwritten by its grid's mean. Bytes,
    // not vector<bool>: threads write neighbouring flags.
    std::vector<unsigned char> supersample(static_cast<std::size_t>(rect.width()) * rect.height());
    const auto flag = [&](int x, int y) -> unsigned char& {
        return supersample[static_cast<std::size_t>(y - rect.y0) * rect.width() + (x - rect.x0)];
    };
    for_each_row(tracers, rect, [&](const Tracer&, int y) {
        for (int x = rect.x0; x < rect.x1; ++x)
            flag(x, y) = needs_supersampling(raster, known, x, y, threshold) ? 1 : 0;
    });
    for_each_row(
        tracers, rect,
        [&](const Tracer& tracer, int y) {
            for (int x = rect.x0; x < rect.x1; ++x) {
                if (flag(x, y) == 0) continue;
                const Spectrum centre = raster.at(x, y);
                raster.set(x, y, tracer.pixel(x, y, &centre));
            }
        },
        progress);
}

}  // namespace

Raster render(const Scene& scene, const RenderOptions& options, RenderStats* stats,
              RenderProgress* progress) {
    return render_region(scene, options, image_rect(scene.viewer), stats, progress);
}

int render_threads(const RenderOptions& options, const PixelRect& region) {
    return std::clamp(worker_threads(options.threads), 1, region.height());
}

Raster render_region(const Scene& scene, const RenderOptions& options, const PixelRect& region,
                     RenderStats* stats, RenderProgress* progress) {
    const PixelRect image = image_rect(scene.viewer);
    if (region.empty() || !image.contains(region))
        throw std::invalid_argument("render_region: the region is empty or outside the image");
    const int threads = render_threads(options, region);
    // One tracer per thread, each counting its own rays; merged once all have joined.
    const std::vector<Tracer> tracers(static_cast<std::size_t>(threads), Tracer(scene, options));
    // Adaptive decisions need the one-ray values of a margin around the region.
    const PixelRect canvas = options.adaptive_threshold ? with_margin(region, image) : region;
    Window raster(canvas);
    if (options.adaptive_threshold) {
        render_adaptive(tracers, region, image, *options.adaptive_threshold, raster, progress);
    } else {
        if (progress != nullptr)
            progress->rows_total.store(static_cast<std::uint64_t>(region.height()));
        for_each_row(
            tracers, region,
            [&](const Tracer& tracer, int y) {
                for (int x = region.x0; x < region.x1; ++x) raster.set(x, y, tracer.pixel(x, y));
            },
            progress);
    }
    if (stats != nullptr)
        for (const Tracer& tracer : tracers) *stats += tracer.stats();
    return raster.crop(region);
}

}  // namespace rt
