// Times rt's stages on each scene file: reading, building the object hierarchy, rendering
// (the median of --repeat renders), the rays traced per second, and the peak memory.
//   rt_bench [--threads N] [--depth N] [--samples N] [--adaptive T] [--repeat N] [--linear]
//            scene.in ...
// --samples and --adaptive are rt's -s and -a (--adaptive without --samples takes 3 x 3, as
// rt does); the ray columns then show what supersampling cost.
// --linear renders with the hierarchy turned off (every ray tests every object).
// Peak memory is the process's peak so far (getrusage's ru_maxrss), so it is the figure of
// one scene only when rt_bench is given one scene; bench/run runs it once per scene.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "batch/statistics.h"
#include "rt/error.h"
#include "rt/reader.h"
#include "rt/render.h"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 == 1 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

double peak_megabytes() { return static_cast<double>(rt::peak_memory_bytes()) / (1024 * 1024); }

struct Figures {
    std::size_t objects = 0;
    double megabytes = 0;  // the scene file's size
    int xres = 0, yres = 0;
    double read_s = 0, build_s = 0, render_s = 0;
    rt::RenderStats rays;
};

Figures measure(const std::string& file, rt::RenderOptions options, int repeat) {
    Figures f;
    auto start = Clock::now();
    std::ifstream in(file, std::ios::binary);
    if (!in) throw rt::Error(file + ": cannot open");
    rt::Scene scene =
        rt::SceneReader(in, file, std::filesystem::path(file).parent_path()).read_scene();
    f.read_s = seconds_since(start);

    start = Clock::now();
    if (options.accelerate) scene.build_index(rt::worker_threads(options.threads));  // as rt does
    f.build_s = seconds_since(start);

    std::vector<double> times;
    for (int i = 0; i < repeat; ++i) {
        rt::RenderStats rays;  // the same every time: rendering is deterministic
        start = Clock::now();
        rt::render(scene, options, &rays);
        times.push_back(seconds_since(start));
        f.rays = rays;
    }
    f.render_s = median(times);
    f.objects = scene.objects.size();
    f.megabytes = static_cast<double>(std::filesystem::file_size(file)) / 1e6;
    f.xres = scene.viewer.xres;
    f.yres = scene.viewer.yres;
    return f;
}

void print_header() {
    std::printf("%-16s %9s %11s %8s %8s %9s %8s %10s %12s %9s %8s %9s %10s %11s\n", "scene",
                "objects", "size", "read_s", "build_s", "render_s", "Mrays/s", "primary_M",
                "secondary_M", "shadow_M", "peak_MB", "tests/ray", "read_MB/s", "build_Mo/s");
}

void print_row(const std::string& name, const Figures& f) {
    const auto millions = [](std::uint64_t n) { return static_cast<double>(n) / 1e6; };
    const std::string size = std::to_string(f.xres) + "x" + std::to_string(f.yres);
    const double tests_per_ray = f.rays.total() > 0 ? static_cast<double>(f.rays.object_tests) /
                                                          static_cast<double>(f.rays.total())
                                                    : 0;
    std::printf(
        "%-16s %9zu %11s %8.3f %8.3f %9.3f %8.2f %10.3f %12.3f %9.3f %8.1f %9.2f %10.1f %11.2f\n",
        name.c_str(), f.objects, size.c_str(), f.read_s, f.build_s, f.render_s,
        millions(f.rays.total()) / f.render_s, millions(f.rays.primary_rays),
        millions(f.rays.secondary_rays()), millions(f.rays.shadow_rays), peak_megabytes(),
        tests_per_ray, f.megabytes / f.read_s,
        f.build_s > 0 ? static_cast<double>(f.objects) / f.build_s / 1e6 : 0.0);
    std::fflush(stdout);
}

int usage() {
    std::cerr << "usage: rt_bench [--threads N] [--depth N] [--samples N] [--adaptive T] "
                 "[--repeat N] [--linear] scene.in ...\n";
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    rt::RenderOptions options;  // rt's defaults: depth 7, weight cut-off 0.01
    int repeat = 1;
    bool have_samples = false;
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        const bool has_value = i + 1 < argc;
        if (arg == "--threads" && has_value) {
            options.threads = std::max(0, std::atoi(argv[++i]));
        } else if (arg == "--depth" && has_value) {
            options.max_depth = std::max(0, std::atoi(argv[++i]));
        } else if (arg == "--samples" && has_value) {
            options.samples = std::clamp(std::atoi(argv[++i]), 1, 64);
            have_samples = true;
        } else if (arg == "--adaptive" && has_value) {
            options.adaptive_threshold = std::max(0.0, std::atof(argv[++i]));
        } else if (arg == "--repeat" && has_value) {
            repeat = std::max(1, std::atoi(argv[++i]));
        } else if (arg == "--linear") {
            options.accelerate = false;
        } else if (arg.starts_with("-")) {
            return usage();
        } else {
            files.push_back(arg);
        }
    }
    if (files.empty()) return usage();
    if (options.adaptive_threshold && !have_samples) options.samples = rt::kDefaultAdaptiveSamples;
    print_header();
    int status = 0;
    for (const std::string& file : files) {
        try {
            print_row(std::filesystem::path(file).stem().string(), measure(file, options, repeat));
        } catch (const std::exception& e) {  // rt::Error for the scene, bad_alloc, ...
            std::cerr << e.what() << "\n";
            status = 1;
        }
    }
    return status;
}
