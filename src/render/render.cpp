#include "rt/render.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

namespace rt {

int worker_threads(int requested) {
    if (requested > 0) return requested;
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

namespace {

// A raster that holds the pixels of `rect` only, addressed by full-image coordinates: a
// region's pixels are computed at their own (x, y), so they are the whole render's pixels.
class Window {
  public:
    explicit Window(const PixelRect& rect) : rect_(rect), raster_(rect.width(), rect.height()) {}
    Spectrum at(int x, int y) const { return raster_.at(x - rect_.x0, y - rect_.y0); }
    void set(int x, int y, const Spectrum& s) { raster_.set(x - rect_.x0, y - rect_.y0, s); }
    // The pixels of `part` (within this window) as a raster of their own; the window's own
    // raster, moved, when the part is all of it (a copy of a 1024 x 1024 raster, 24 MiB in
    // fresh pages, was 4 % of the SPD teapot's whole run).
    Raster crop(const PixelRect& part) && {
        if (part == rect_) return std::move(raster_);
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
void for_each_row(std::vector<Tracer>& tracers, const PixelRect& rect, const Work& work,
                  RenderProgress* progress = nullptr) {
    std::atomic<int> next_row{rect.y0};
    auto worker = [&](Tracer& tracer) {
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
        pool.emplace_back(worker, std::ref(tracers[i]));
    worker(tracers[0]);
}  // every worker joins here

// One row of one pass, through the store when there is one: restored if it holds the row,
// else computed by `trace(x)` for every column and handed to it.
template <typename Trace>
void row_through_store(RowStore* store, int pass, int y, int x0, int x1, Window& raster,
                       std::vector<double>& scratch, const Trace& trace) {
    if (store == nullptr) {
        for (int x = x0; x < x1; ++x) raster.set(x, y, trace(x));
        return;
    }
    scratch.resize(static_cast<std::size_t>(x1 - x0) * kSpectrumComponents);
    const auto at = [&](int x) {
        return scratch.data() + static_cast<std::size_t>(x - x0) * kSpectrumComponents;
    };
    if (store->restore(pass, y, x0, x1, scratch.data())) {
        for (int x = x0; x < x1; ++x) {
            Spectrum s;
            for (std::size_t i = 0; i < kSpectrumComponents; ++i) s[i] = at(x)[i];
            raster.set(x, y, s);
        }
        return;
    }
    for (int x = x0; x < x1; ++x) {
        const Spectrum s = trace(x);
        raster.set(x, y, s);
        for (std::size_t i = 0; i < kSpectrumComponents; ++i) at(x)[i] = s[i];
    }
    store->finished(pass, y, x0, x1, scratch.data());
}

// Row y's one ray per pixel from x0 to x1 - 1, through the store as row_through_store: the
// row's rays are made before any is traced (Tracer::row_rays), so that their square roots
// and divisions overlap.
void one_ray_row(Tracer& tracer, RowStore* store, int pass, int y, int x0, int x1, Window& raster) {
    thread_local std::vector<double> scratch;
    thread_local std::vector<Ray> rays;
    tracer.row_rays(y, x0, x1, rays);
    row_through_store(store, pass, y, x0, x1, raster, scratch, [&](int x) {
        return tracer.shade_primary(rays[static_cast<std::size_t>(x - x0)]);
    });
}

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
void render_adaptive(std::vector<Tracer>& tracers, const PixelRect& rect, const PixelRect& image,
                     double threshold, Window& raster, RenderProgress* progress, RowStore* store) {
    const PixelRect known = one_ray_rect(rect, image);
    // The one-ray pass and the grid pass trace; deciding is quick and not counted.
    if (progress != nullptr)
        progress->rows_total.store(
            static_cast<std::uint64_t>((known.y1 - known.y0) + rect.height()));
    for_each_row(
        tracers, known,
        [&](Tracer& tracer, int y) {
            one_ray_row(tracer, store, 0, y, known.x0, known.x1, raster);
        },
        progress);
    // Decided for the whole rectangle before any pixel is overwritten by its grid's mean. Bytes,
    // not vector<bool>: threads write neighbouring flags.
    std::vector<unsigned char> supersample(static_cast<std::size_t>(rect.width()) * rect.height());
    const auto flag = [&](int x, int y) -> unsigned char& {
        return supersample[static_cast<std::size_t>(y - rect.y0) * rect.width() + (x - rect.x0)];
    };
    for_each_row(tracers, rect, [&](Tracer&, int y) {
        for (int x = rect.x0; x < rect.x1; ++x)
            flag(x, y) = needs_supersampling(raster, known, x, y, threshold) ? 1 : 0;
    });
    for_each_row(
        tracers, rect,
        [&](Tracer& tracer, int y) {
            thread_local std::vector<double> scratch;
            row_through_store(store, 1, y, rect.x0, rect.x1, raster, scratch, [&](int x) {
                const Spectrum centre = raster.at(x, y);
                return flag(x, y) == 0 ? centre : tracer.pixel(x, y, &centre);
            });
        },
        progress);
}

}  // namespace

Raster render(const Scene& scene, const RenderOptions& options, RenderStats* stats,
              RenderProgress* progress) {
    return render_region(scene, options, image_rect(scene.viewer), stats, progress);
}

PixelRect one_ray_rect(const PixelRect& r, const PixelRect& image) {
    return {std::max(r.x0 - 1, image.x0), std::max(r.y0 - 1, image.y0),
            std::min(r.x1 + 1, image.x1), std::min(r.y1 + 1, image.y1)};
}

int render_threads(const RenderOptions& options, const PixelRect& region) {
    return std::clamp(worker_threads(options.threads), 1, region.height());
}

Raster render_region(const Scene& scene, const RenderOptions& options, const PixelRect& region,
                     RenderStats* stats, RenderProgress* progress, RowStore* rows) {
    const PixelRect image = image_rect(scene.viewer);
    if (region.empty() || !image.contains(region))
        throw std::invalid_argument("render_region: the region is empty or outside the image");
    const int threads = render_threads(options, region);
    // One tracer per thread, each counting its own rays; merged once all have joined.
    std::vector<Tracer> tracers(static_cast<std::size_t>(threads), Tracer(scene, options));
    // Adaptive decisions need the one-ray values of a margin around the region.
    const PixelRect canvas = options.adaptive_threshold ? one_ray_rect(region, image) : region;
    Window raster(canvas);
    if (options.adaptive_threshold) {
        render_adaptive(tracers, region, image, *options.adaptive_threshold, raster, progress,
                        rows);
    } else {
        if (progress != nullptr)
            progress->rows_total.store(static_cast<std::uint64_t>(region.height()));
        for_each_row(
            tracers, region,
            [&](Tracer& tracer, int y) {
                // One ray a pixel is what pixel() traces then.
                if (options.samples <= 1) {
                    one_ray_row(tracer, rows, 1, y, region.x0, region.x1, raster);
                    return;
                }
                thread_local std::vector<double> scratch;
                row_through_store(rows, 1, y, region.x0, region.x1, raster, scratch,
                                  [&](int x) { return tracer.pixel(x, y); });
            },
            progress);
    }
    if (stats != nullptr)
        for (const Tracer& tracer : tracers) *stats += tracer.stats();
    return std::move(raster).crop(region);
}

}  // namespace rt
