// rt: reads a scene, traces it and writes a PPM, PNG or PFM image (section 1.10.3 of the
// original).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <iostream>
#include <new>
#include <optional>

#include "rt/cli.h"
#include "rt/error.h"
#include "rt/image_io.h"
#include "rt/ppm.h"
#include "rt/progress.h"
#include "rt/reader.h"
#include "rt/statistics.h"
#include "rt/trace.h"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitError = 1;  // a scene, texture or input/output error
constexpr int kExitUsage = 2;  // the command line made no sense

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// --size: the viewer's vectors stay, so the field of view does; say when pixels stop being
// square, and which size would keep them so.
void apply_size(rt::Viewer& viewer, const rt::ImageSize& size, bool quiet) {
    // A size in the scene's own proportions keeps its pixels' shape, square or not.
    const bool same_shape =
        std::lround(static_cast<double>(size.width) * viewer.yres / viewer.xres) == size.height ||
        std::lround(static_cast<double>(size.height) * viewer.xres / viewer.yres) == size.width;
    viewer.xres = size.width;
    viewer.yres = size.height;
    if (quiet || same_shape) return;
    if (const auto square = rt::square_pixel_height(viewer))
        std::cerr << "rt: warning: --size " << size.width << "x" << size.height
                  << " gives non-square pixels (the viewer's x and y vectors are "
                  << rt::format_number(length(viewer.x) / length(viewer.y))
                  << " : 1); for square pixels use --size " << size.width << "x" << *square
                  << ", or change the viewer's vectors\n";
}

int run(const rt::CommandLine& cl) {
    rt::RunStatistics statistics;
    const int threads = rt::worker_threads(cl.render.threads);
    rt::Scene scene = rt::read_scene_file(cl.input, threads, &statistics.times);
    if (cl.size) apply_size(scene.viewer, *cl.size, cl.quiet);
    if (cl.read_only) {
        const std::string name = cl.input == "-" ? "<stdin>" : cl.input;
        std::cout << name << ": " << scene.objects.size() << " objects, " << scene.lights.size()
                  << " lights, " << scene.viewer.xres << "x" << scene.viewer.yres;
        if (const std::size_t n = scene.skipped_triangles; n != 0)
            std::cout << ", " << n << " zero-area " << (n == 1 ? "triangle" : "triangles")
                      << " skipped";
        std::cout << "\n";
        return kExitOk;
    }
    // The output file is claimed before rendering, so a bad path fails fast, and is only
    // replaced once the whole image has been written.
    rt::ImageEncoding encoding = cl.image;
    encoding.metadata = rt::image_metadata(cl);
    rt::OutputFile output(cl.output);

    rt::RenderProgress progress;
    std::optional<rt::ProgressDisplay> display;
    if (!cl.quiet && (cl.progress || isatty(STDERR_FILENO) != 0))
        display.emplace(progress,
                        isatty(STDERR_FILENO) != 0 ? rt::ProgressDisplay::Style::terminal
                                                   : rt::ProgressDisplay::Style::lines,
                        std::cerr);
    auto start = Clock::now();
    const rt::Raster image = rt::render(scene, cl.render, &statistics.rays, &progress);
    statistics.times.render = seconds_since(start);
    if (display) display->finish();

    start = Clock::now();
    output.write_bytes(rt::encode_image(image, encoding));
    statistics.times.write = seconds_since(start);
    if (cl.stats) {
        statistics.threads = std::clamp(threads, 1, scene.viewer.yres);
        statistics.objects = scene.objects.size();
        statistics.lights = scene.lights.size();
        statistics.peak_memory_bytes = rt::peak_memory_bytes();
        std::cerr << rt::format_statistics(statistics);
    }
    return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
    rt::CommandLine cl;
    try {
        cl = rt::parse_command_line({argv + 1, argv + argc});
    } catch (const rt::UsageError& e) {
        std::cerr << "rt: " << e.message << "\nTry 'rt --help' for more information.\n";
        return kExitUsage;
    }
    if (cl.help) {
        std::cout << rt::usage_text();
        return kExitOk;
    }
    if (cl.version) {
        std::cout << "rt " RT_VERSION "\n";
        return kExitOk;
    }
    try {
        return run(cl);
    } catch (const rt::Error& e) {
        std::cerr << e.what() << "\n";
    } catch (const std::bad_alloc&) {
        std::cerr << "rt: out of memory\n";
    } catch (const std::exception& e) {
        std::cerr << "rt: " << e.what() << "\n";
    }
    return kExitError;
}
