#include "rt/trace.h"

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
    : scene_(scene), options_(options), last_blockers_(scene.lights.size()) {
    if (options_.accelerate && !scene_.index.covers(scene_.objects.size()))
        throw std::logic_error("Tracer: the scene's index was not built (Scene::build_index)");
}

std::optional<SceneHit> Tracer::closest_hit(const Ray& ray) const {
    Interval range{hit_tolerance(ray.origin), kInfinity};
    if (options_.accelerate) {
        ObjectIndex::Found found;
        if (!scene_.index.closest(ray, range, found)) return std::nullopt;
        return SceneHit{&scene_.objects[found.object], found.hit};
    }
    // The linear scan: every object in file order.
    std::optional<SceneHit> best;
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

bool Tracer::blocked(const Ray& ray, double distance, ObjectIndex::Blocker* last) const {
    ++stats_.shadow_rays;
    const Interval range{hit_tolerance(ray.origin), distance};
    if (options_.accelerate) return scene_.index.any(ray, range, last);
    return std::any_of(scene_.objects.begin(), scene_.objects.end(),
                       [&](const Object& o) { return o.shape.intersect_any(ray, range); });
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
    ++(depth == 0 ? stats_.primary_rays : stats_.secondary_rays);
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
    if (split.refracted && kt > 0 && options_.refraction && may_trace(depth + 1, weight * kt))
        result += kt * trace({point, *split.refracted}, depth + 1, weight * kt, next_ior,
                             leaving ? Spectrum(0.0) : m.absorption);

    if (options_.ambient) result += scene_.ambient * m.colour * m.kd;
    const Vec3 reflected = reflect(ray.direction, facing);
    if (options_.diffuse || options_.specular)
        result += direct_light(point, facing, reflected, m, split.highlight);
    // The reflected ray stays in the medium it came through.
    const double ks = split.mirror;
    if (ks > 0 && options_.reflection && may_trace(depth + 1, weight * ks))
        result += ks * trace({point, reflected}, depth + 1, weight * ks, ior, absorption);
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

Spectrum Tracer::pixel(int x, int y) const {
    const int n = options_.samples;
    if (n <= 1) return shade_primary(scene_.viewer.primary_ray(x, y));
    // Samples on a regular n x n grid from the pixel's corner, so that one sample per pixel
    // is exactly the original's ray.
    Spectrum sum(0.0);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            sum += shade_primary(scene_.viewer.primary_ray(x + static_cast<double>(i) / n,
                                                           y + static_cast<double>(j) / n));
    return sum * (1.0 / (n * n));
}

int worker_threads(int requested) {
    if (requested > 0) return requested;
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

Raster render(const Scene& scene, const RenderOptions& options, RenderStats* stats) {
    const Viewer& v = scene.viewer;
    Raster raster(v.xres, v.yres);
    const int threads = std::clamp(worker_threads(options.threads), 1, v.yres);
    // One tracer per thread, each counting its own rays; merged once all have joined.
    std::vector<Tracer> tracers(static_cast<std::size_t>(threads), Tracer(scene, options));
    std::atomic<int> next_row{0};
    auto work = [&](const Tracer& tracer) {
        for (int y = next_row++; y < v.yres; y = next_row++)
            for (int x = 0; x < v.xres; ++x) raster.set(x, y, tracer.pixel(x, y));
    };
    {
        std::vector<std::jthread> pool;
        for (std::size_t i = 1; i < tracers.size(); ++i)
            pool.emplace_back(work, std::cref(tracers[i]));
        work(tracers[0]);
    }  // every worker has joined here
    if (stats != nullptr)
        for (const Tracer& tracer : tracers) *stats += tracer.stats();
    return raster;
}

}  // namespace rt
