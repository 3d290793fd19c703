// RenderOptions::queries, the hook through which another library can answer the tracer's ray
// queries (bench/embree): a backend written here that scans every object in file order, as
// --no-bvh does, must give every scene in scenes/ the same image as rt's own hierarchy, to
// the bit, on one thread and two; and the tracer must ask it every query and nothing else.
#include <atomic>
#include <filesystem>
#include <stdexcept>

#include "check.h"
#include "cli_util.h"
#include "rt/reader.h"
#include "rt/render.h"
#include "rt/trace.h"
#include "scene_util.h"

namespace fs = std::filesystem;
using namespace rt;

namespace {

// The linear scan, outside the tracer, counting what it is asked.
class ScanQueries : public RayQueries {
  public:
    explicit ScanQueries(const Scene& scene) : scene_(scene) {}

    bool closest(const Ray& ray, Interval range, SceneHit& found) const override {
        closest_calls.fetch_add(1, std::memory_order_relaxed);
        bool any_hit = false;
        for (const Object& object : scene_.objects) {
            Hit hit;
            if (!object.shape.intersect(ray, range, hit)) continue;
            found = {&object, hit};
            range.t_max = hit.t;
            any_hit = true;
        }
        return any_hit;
    }
    bool any(const Ray& ray, Interval range) const override {
        any_calls.fetch_add(1, std::memory_order_relaxed);
        for (const Object& object : scene_.objects)
            if (object.shape.intersect_any(ray, range)) return true;
        return false;
    }

    mutable std::atomic<std::uint64_t> closest_calls{0};
    mutable std::atomic<std::uint64_t> any_calls{0};

  private:
    const Scene& scene_;
};

// Small enough that every scene renders in a moment; the pixels still cover every object.
Scene small_scene(const fs::path& file) {
    Scene scene = read_scene_file(file.string());
    scene.viewer.xres = 40;
    scene.viewer.yres = 40;
    return scene;
}

}  // namespace

TEST(every_scene_renders_the_same_through_the_hook) {
    const auto files = rt_test::files_with_extension(fs::path(RT_SOURCE_DIR) / "scenes", ".in");
    CHECK(files.size() > 20);
    for (const fs::path& file : files) {
        const Scene scene = small_scene(file);
        for (const int threads : {1, 2}) {
            RenderOptions options;
            options.threads = threads;
            RenderStats own;
            const Raster expected = render(scene, options, &own);
            const ScanQueries scan(scene);
            options.queries = &scan;
            RenderStats hooked;
            const Raster actual = render(scene, options, &hooked);
            if (!rt_test::identical(actual, expected))
                rt_test::record_failure(
                    __FILE__, __LINE__,
                    rt_test::join(file.filename().string(), " on ", threads,
                                  " threads: the image through the hook differs"));
            // The same ray tree, every query of it asked of the backend.
            CHECK_EQ(hooked.primary_rays, own.primary_rays);
            CHECK_EQ(hooked.secondary_rays(), own.secondary_rays());
            CHECK_EQ(hooked.shadow_rays, own.shadow_rays);
            CHECK_EQ(scan.closest_calls.load(), own.primary_rays + own.secondary_rays());
            CHECK_EQ(scan.any_calls.load(), own.shadow_rays);
            CHECK_EQ(hooked.object_tests, std::uint64_t{0});  // the backend's are its own
        }
    }
}

TEST(every_render_mode_goes_through_the_hook) {
    const Scene scene = small_scene(fs::path(RT_SOURCE_DIR) / "scenes" / "showcase.in");
    for (const RenderMode mode : {RenderMode::depth, RenderMode::colour, RenderMode::normal}) {
        RenderOptions options;
        options.mode = mode;
        const Raster expected = render(scene, options);
        const ScanQueries scan(scene);
        options.queries = &scan;
        CHECK(rt_test::identical(render(scene, options), expected));
        CHECK_EQ(scan.closest_calls.load(), std::uint64_t{40 * 40});
        CHECK_EQ(scan.any_calls.load(), std::uint64_t{0});
    }
}

TEST(a_backend_needs_no_hierarchy) {
    // A scene whose index was never built: rt's own tracer refuses it, a backend answers.
    std::string text = rt_test::kTestViewer;
    text += "104  0 0 5  1 1 1\n1  1  0 0 0  100  0.9 0.3 0.2  0.3 40  0.8  0 1\n";
    Scene scene = rt_test::parse_scene(text);
    scene.index.reset();
    RenderOptions options;
    bool refused = false;
    try {
        (void)render(scene, options);
    } catch (const std::logic_error&) {
        refused = true;
    }
    CHECK(refused);
    const ScanQueries scan(scene);
    options.queries = &scan;
    options.accelerate = false;
    const Raster oracle = render(scene, options);
    options.accelerate = true;
    CHECK(rt_test::identical(render(scene, options), oracle));
}
