// Prints figures: the time to render scenes, and intersection throughput per primitive type.
//   rt_bench [--threads N] [--repeat N] scene.in ...
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "rt/error.h"
#include "rt/reader.h"
#include "rt/trace.h"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// The best of several runs is the least disturbed by other work on the machine.
double best_render_seconds(const rt::Scene& scene, const rt::RenderOptions& options, int repeat) {
    double best = 1e300;
    for (int i = 0; i < repeat; ++i) {
        const auto start = Clock::now();
        const rt::Raster raster = rt::render(scene, options);
        best = std::min(best, seconds_since(start));
        if (raster.width() == 0) std::abort();
    }
    return best;
}

// Intersection tests per second for each object in the scene, against the primary rays.
void intersection_rates(const rt::Scene& scene) {
    const rt::Viewer& v = scene.viewer;
    std::vector<rt::Ray> rays;
    for (int y = 0; y < v.yres; y += 2)
        for (int x = 0; x < v.xres; x += 2) rays.push_back(v.primary_ray(x, y));
    for (const rt::Object& object : scene.objects) {
        const auto start = Clock::now();
        std::size_t tests = 0, hits = 0;
        while (seconds_since(start) < 0.05) {
            for (const rt::Ray& ray : rays) {
                rt::Hit hit;
                hits += object.shape.intersect(ray, {1e-7, rt::kInfinity}, hit) ? 1 : 0;
            }
            tests += rays.size();
        }
        const double rate = static_cast<double>(tests) / seconds_since(start);
        std::cout << "    " << object.shape.type->name << ": " << rate / 1e6
                  << " M intersections/s ("
                  << 100.0 * static_cast<double>(hits) / static_cast<double>(tests) << "% hit)\n";
    }
}

}  // namespace

int main(int argc, char** argv) {
    int threads = 0, repeat = 3;
    std::vector<std::string> scenes;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--threads" && i + 1 < argc) {
            threads = std::atoi(argv[++i]);
        } else if (arg == "--repeat" && i + 1 < argc) {
            repeat = std::max(1, std::atoi(argv[++i]));
        } else {
            scenes.push_back(arg);
        }
    }
    try {
        for (const std::string& file : scenes) {
            const rt::Scene scene = rt::read_scene_file(file);
            rt::RenderOptions options;
            options.threads = threads;
            const double s = best_render_seconds(scene, options, repeat);
            const double pixels = static_cast<double>(scene.viewer.xres) * scene.viewer.yres;
            std::cout << file << ": " << scene.viewer.xres << "x" << scene.viewer.yres << ", "
                      << scene.objects.size() << " objects, best of " << repeat << ": " << s * 1000
                      << " ms (" << pixels / s / 1e6 << " Mpixels/s, threads "
                      << (threads > 0 ? std::to_string(threads) : "auto") << ")\n";
            intersection_rates(scene);
        }
    } catch (const rt::Error& e) {
        std::cerr << e.what() << "\n";
        return 1;
    }
    return 0;
}
