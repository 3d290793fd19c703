#include "rt/render.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <span>
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
    // Pixels x0 ... of row y, three values each.
    void put_row(int y, int x0, std::span<const double> values) {
        raster_.set_row(y - rect_.y0, x0 - rect_.x0, values);
    }
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

// The same for a render that keeps only the samples its file will hold: each row quantized
// as it is put, by the function the writers use, so the samples are those of the raster.
class SampleWindow {
  public:
    SampleWindow(const PixelRect& rect, int bits, const Gamma& gamma)
        : rect_(rect), samples_(rect.width(), rect.height(), bits, gamma) {}
    void put_row(int y, int x0, std::span<const double> values) {
        const std::size_t bytes_per_pixel = samples_.shape().bytes_per_pixel();
        quantize_values(
            values, samples_.bits(), samples_.gamma(),
            samples_.row(y - rect_.y0) + static_cast<std::size_t>(x0 - rect_.x0) * bytes_per_pixel);
    }
    SampleRaster take() && { return std::move(samples_); }

  private:
    PixelRect rect_;
    SampleRaster samples_;
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
// else computed by `trace(x)` for every column and handed to it. The row is gathered in a
// buffer of the thread's own and put in `out` whole.
template <typename Pixels, typename Trace>
void row_through_store(RowStore* store, int pass, int y, int x0, int x1, Pixels& out,
                       const Trace& trace) {
    thread_local std::vector<double> row;
    row.resize(static_cast<std::size_t>(x1 - x0) * kSpectrumComponents);
    if (store == nullptr || !store->restore(pass, y, x0, x1, row.data())) {
        double* at = row.data();
        for (int x = x0; x < x1; ++x) {
            const Spectrum s = trace(x);
            for (std::size_t i = 0; i < kSpectrumComponents; ++i) *at++ = s[i];
        }
        if (store != nullptr) store->finished(pass, y, x0, x1, row.data());
    }
    out.put_row(y, x0, row);
}

// Row y's one ray per pixel from x0 to x1 - 1, through the store as row_through_store: the
// row's rays are made before any is traced (Tracer::row_rays), so that their square roots
// and divisions overlap.
template <typename Pixels>
void one_ray_row(Tracer& tracer, RowStore* store, int pass, int y, int x0, int x1, Pixels& out) {
    thread_local std::vector<Ray> rays;
    thread_local std::vector<unsigned char> spared;
    const std::size_t blanks = tracer.row_rays(y, x0, x1, rays, spared);
    const Spectrum blank = tracer.blank_pixel();
    row_through_store(store, pass, y, x0, x1, out, [&](int x) {
        const auto i = static_cast<std::size_t>(x - x0);
        if (i == 0) tracer.count_blank_pixels(blanks);  // traced, not restored: counted
        return spared[i] != 0 ? blank : tracer.shade_pixel_ray(rays[i], x, y);
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
            // The row is put once it is whole, so each pixel's own one-ray value is read here.
            row_through_store(store, 1, y, rect.x0, rect.x1, raster, [&](int x) {
                const Spectrum centre = raster.at(x, y);
                return flag(x, y) == 0 ? centre : tracer.pixel(x, y, &centre);
            });
        },
        progress);
}

// Every pixel of `region` without adaptive supersampling, into `out`.
template <typename Pixels>
void render_rows(std::vector<Tracer>& tracers, const RenderOptions& options,
                 const PixelRect& region, Pixels& out, RenderProgress* progress, RowStore* rows) {
    if (progress != nullptr)
        progress->rows_total.store(static_cast<std::uint64_t>(region.height()));
    for_each_row(
        tracers, region,
        [&](Tracer& tracer, int y) {
            // One ray a pixel is what pixel() traces then.
            if (options.samples <= 1)
                return one_ray_row(tracer, rows, 1, y, region.x0, region.x1, out);
            row_through_store(rows, 1, y, region.x0, region.x1, out,
                              [&](int x) { return tracer.pixel(x, y); });
        },
        progress);
}

// Checks the region, makes one tracer per thread (each counting its own rays), runs
// `render(tracers)` and adds their counts into `stats` once all have joined.
template <typename Render>
auto with_tracers(const Scene& scene, const RenderOptions& options, const PixelRect& region,
                  RenderStats* stats, const Render& render) {
    const PixelRect image = image_rect(scene.viewer);
    if (region.empty() || !image.contains(region))
        throw std::invalid_argument("render_region: the region is empty or outside the image");
    const int threads = render_threads(options, region);
    // The tracers' primary mask covers the pixels traced: the region, and with -a the
    // one-ray margin around it.
    std::vector<Tracer> tracers(static_cast<std::size_t>(threads),
                                Tracer(scene, options, one_ray_rect(region, image)));
    auto result = render(tracers);
    if (stats != nullptr)
        for (const Tracer& tracer : tracers) *stats += tracer.stats();
    return result;
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
    return with_tracers(scene, options, region, stats, [&](std::vector<Tracer>& tracers) {
        if (!options.adaptive_threshold) {
            Window raster(region);
            render_rows(tracers, options, region, raster, progress, rows);
            return std::move(raster).crop(region);
        }
        // Adaptive decisions need the one-ray values of a margin around the region.
        Window raster(one_ray_rect(region, image_rect(scene.viewer)));
        render_adaptive(tracers, region, image_rect(scene.viewer), *options.adaptive_threshold,
                        raster, progress, rows);
        return std::move(raster).crop(region);
    });
}

SampleRaster render_region_samples(const Scene& scene, const RenderOptions& options,
                                   const PixelRect& region, int bits, const Gamma& gamma,
                                   RenderStats* stats, RenderProgress* progress, RowStore* rows) {
    // Adaptive decisions compare neighbours' one-ray values, which samples do not keep.
    if (options.adaptive_threshold)
        return quantize_raster(render_region(scene, options, region, stats, progress, rows), bits,
                               gamma);
    return with_tracers(scene, options, region, stats, [&](std::vector<Tracer>& tracers) {
        SampleWindow samples(region, bits, gamma);
        render_rows(tracers, options, region, samples, progress, rows);
        return std::move(samples).take();
    });
}

}  // namespace rt
