// The image loop: every pixel of an image, or of a region of it, traced on threads that
// share its rows.
#pragma once

#include <atomic>
#include <cstdint>

#include "rt/image_io.h"
#include "rt/options.h"
#include "rt/raster.h"
#include "rt/scene.h"
#include "rt/trace.h"

namespace rt {

// What a render has done so far, for a progress display on another thread. Each thread
// publishes once per row it finishes: rows of every pass that traces, and rays traced.
struct RenderProgress {
    std::atomic<std::uint64_t> rows_total{0};
    std::atomic<std::uint64_t> rows_done{0};
    std::atomic<std::uint64_t> rows_restored{0};  // of rows_done: taken from a RowStore
    std::atomic<std::uint64_t> rays{0};
};

// Rows kept between runs (rt's --checkpoint): a render given a store takes from it every row
// it holds instead of tracing it, and hands it every row it finishes. Pass 0 is the one-ray
// pass of adaptive supersampling (over the region and its one-pixel margin), pass 1 the
// final values. The render's threads call it at once, so it must be thread-safe. Values are
// three per pixel, columns x0 to x1 - 1 of row y in full-image coordinates.
class RowStore {
  public:
    virtual ~RowStore() = default;
    // Fills `values` and returns true when the store holds that row.
    virtual bool restore(int pass, int y, int x0, int x1, double* values) = 0;
    virtual void finished(int pass, int y, int x0, int x1, const double* values) = 0;
};

// Renders every pixel of the scene's viewer. Rows are shared among threads, and each pixel
// depends on nothing else, so the result is the same whatever the number of threads. With
// options.adaptive_threshold, every pixel is first traced with the original's one ray, and
// only the pixels that differ from a 4-connected neighbour by more than the threshold (in some
// component, both clamped to [0, 1]) are replaced by their options.samples^2 grid: exactly the
// value Tracer::pixel gives them. When stats is given, the counts of every thread are added
// into it.
Raster render(const Scene& scene, const RenderOptions& options, RenderStats* stats = nullptr,
              RenderProgress* progress = nullptr);

// The viewer's whole image as a rectangle.
inline PixelRect image_rect(const Viewer& v) { return {0, 0, v.xres, v.yres}; }

// Renders only `region` (within the viewer's image, not empty; std::invalid_argument
// otherwise) into a raster of its size. Each pixel is traced at its own place in the full
// image, and adaptive decisions see the one-ray values of a one-pixel margin around the
// region, so every pixel equals the same pixel of render(), whatever the thread count.
// With `rows`, held rows are restored rather than traced (they count as done for `progress`,
// with no rays) and finished ones handed to it; the raster is the same either way.
Raster render_region(const Scene& scene, const RenderOptions& options, const PixelRect& region,
                     RenderStats* stats = nullptr, RenderProgress* progress = nullptr,
                     RowStore* rows = nullptr);

// The same pixels as render_region's, kept only as the samples a PPM or PNG file of `bits`
// bits per sample and `gamma` stores (quantize's, to the bit): 3 or 6 bytes a pixel instead
// of a raster's 24, quantized row by row as the threads finish them. With adaptive
// supersampling, whose decisions compare one-ray values, the region is rendered as a raster
// and then quantized.
SampleRaster render_region_samples(const Scene& scene, const RenderOptions& options,
                                   const PixelRect& region, int bits, const Gamma& gamma,
                                   RenderStats* stats = nullptr, RenderProgress* progress = nullptr,
                                   RowStore* rows = nullptr);

// The pixels -a's one-ray pass covers for `region` of `image`: the region and a one-pixel
// margin around it, within the image (adaptive decisions at the region's edges need them).
PixelRect one_ray_rect(const PixelRect& region, const PixelRect& image);

// The number of threads a render uses for RenderOptions::threads (0: one per hardware thread).
int worker_threads(int requested);

// The threads render_region uses: options.threads (or one per hardware thread), but never
// more than the region has rows, since rows are what they share.
int render_threads(const RenderOptions& options, const PixelRect& region);

}  // namespace rt
