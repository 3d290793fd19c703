// rt: reads a scene, traces it and writes a PPM, PNG or PFM image (section 1.10.3 of the
// original).
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iostream>
#include <new>
#include <optional>
#include <sstream>
#include <system_error>
#include <thread>

#include "batch/cli.h"
#include "batch/cost.h"
#include "batch/depfile.h"
#include "rt/error.h"
#include "rt/image_io.h"
#include "common/interrupt.h"
#include "batch/jobserver.h"
#include "common/message_text.h"
#include "common/output_file.h"
#include "batch/progress.h"
#include "rt/reader.h"
#include "batch/statistics.h"
#include "rt/render.h"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitError = 1;  // a scene, texture or input/output error
constexpr int kExitUsage = 2;  // the command line made no sense

// A command line that makes sense only once the scene is read (--region outside the image).
struct LateUsageError {
    std::string message;
};

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

// Text for standard output (--help, --version, -r): a full disk or a closed pipe is an error,
// not a silent success.
int print(std::string_view text) {
    errno = 0;
    std::cout << text;
    std::cout.flush();
    if (std::cout && std::fflush(stdout) == 0 && !std::ferror(stdout)) return kExitOk;
    const int error = errno;
    std::cerr << "rt: cannot write to standard output" << (error != 0 ? ": " : "")
              << (error != 0 ? std::strerror(error) : "") << "\n";
    return kExitError;
}

// The thread count: -j N when given; else, under make's jobserver, one plus the tokens free
// now (no more than the hardware has); else one per hardware thread.
int choose_threads(const rt::CommandLine& cl, const rt::JobserverAuth& auth,
                   std::optional<rt::JobserverClient>& jobs) {
    if (cl.render.threads > 0) return cl.render.threads;
    const int hardware = rt::worker_threads(0);
    if (auth.kind == rt::JobserverAuth::Kind::none) return hardware;
    if (auth.kind == rt::JobserverAuth::Kind::disabled) return 1;
    jobs.emplace(auth);
    if (!jobs->usable()) {
        std::cerr << "rt: warning: " << rt::printable_message(jobs->problem())
                  << "; rendering on 1 thread (-j N sets "
                  << "the number)\n";
        return 1;
    }
    return 1 + jobs->acquire(hardware - 1);
}

int run(const rt::CommandLine& cl, int threads) {
    rt::RunStatistics statistics;
    std::vector<std::filesystem::path> textures;
    rt::Scene scene = rt::read_scene_file(cl.input, threads, &statistics.times, &textures);
    if (cl.size) apply_size(scene.viewer, *cl.size, cl.quiet);
    const rt::PixelRect region = cl.region.value_or(rt::image_rect(scene.viewer));
    if (const auto problem = rt::region_problem(region, scene.viewer.xres, scene.viewer.yres))
        throw LateUsageError{*problem};
    if (cl.read_only) {
        std::ostringstream summary;
        const std::string name =
            cl.input == "-" ? "<stdin>" : rt::show_token(cl.input, rt::kShowWhole);
        summary << name << ": " << scene.objects.size() << " objects, " << scene.lights.size()
                << " lights, " << scene.viewer.xres << "x" << scene.viewer.yres;
        if (const std::size_t n = scene.skipped_triangles; n != 0)
            summary << ", " << n << " zero-area " << (n == 1 ? "triangle" : "triangles")
                    << " skipped";
        summary << "\n";
        return print(summary.view());
    }
    if (!cl.quiet)
        for (const std::string& warning : rt::cost_warnings(scene, cl.render))
            std::cerr << "rt: warning: " << rt::printable_message(warning) << "\n";
    // The output files are checked and claimed before rendering, so a bad path fails fast,
    // and are only replaced once complete. The files the render reads are never written over.
    rt::ImageEncoding encoding = cl.image;
    encoding.metadata = rt::image_metadata(cl);
    if (cl.region)
        rt::add_region_metadata(encoding.metadata, region, scene.viewer.xres, scene.viewer.yres);
    std::vector<std::filesystem::path> inputs = textures;
    inputs.insert(inputs.begin(), cl.input == "-" ? std::string() : cl.input);  // scene first
    rt::OutputFile output(cl.output, inputs);
    std::optional<rt::OutputFile> depfile;
    std::string rule;
    if (!cl.depfile.empty()) {
        std::vector<std::string> dependencies;
        if (cl.input != "-") dependencies.push_back(cl.input);
        for (const auto& texture : textures) dependencies.push_back(texture.string());
        rule = rt::make_rule(cl.output, dependencies);
        std::error_code ec;
        if (std::filesystem::weakly_canonical(cl.depfile, ec) ==
            std::filesystem::weakly_canonical(cl.output, ec))
            throw rt::Error(cl.depfile + ": -M and -o name the same file");
        depfile.emplace(cl.depfile, inputs, "the dependency rule");
    }
    rt::RenderOptions options = cl.render;
    options.threads = threads;

    rt::RenderProgress progress;
    std::optional<rt::ProgressDisplay> display;
    if (!cl.quiet && (cl.progress || isatty(STDERR_FILENO) != 0))
        display.emplace(progress,
                        isatty(STDERR_FILENO) != 0 ? rt::ProgressDisplay::Style::terminal
                                                   : rt::ProgressDisplay::Style::lines,
                        std::cerr);
    auto start = Clock::now();
    const rt::Raster image = rt::render_region(scene, options, region, &statistics.rays, &progress);
    statistics.times.render = seconds_since(start);
    if (display) display->finish();

    start = Clock::now();
    output.write_bytes(rt::encode_image(image, encoding));
    statistics.times.write = seconds_since(start);
    // Written only once the image is: a rule for an image that failed would be a lie.
    if (depfile) depfile->write_bytes(rule);
    if (cl.stats) {
        statistics.threads = rt::render_threads(options, region);
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
        std::cerr << "rt: " << rt::printable_message(e.message)
                  << "\nTry 'rt --help' for more information.\n";
        return kExitUsage;
    }
    if (cl.help) return print(rt::usage_text());
    if (cl.version) return print("rt " RT_VERSION "\n");
    // The jobserver is read before rt opens any file (see JobserverClient).
    const char* makeflags = std::getenv("MAKEFLAGS");
    const rt::JobserverAuth auth = rt::parse_makeflags(makeflags != nullptr ? makeflags : "");
    if (auth.dry_run) return kExitOk;  // make -n, -q and -t run '+' lines too
    rt::interrupt::install_handlers();
    // Declared before anything that can fail, so its tokens go back on every exit path.
    std::optional<rt::JobserverClient> jobs;
    try {
        const int threads = choose_threads(cl, auth, jobs);
        if (const char* debug = std::getenv("RT_DEBUG");
            debug != nullptr && std::strstr(debug, "threads") != nullptr)
            std::cerr << "rt: " << threads << (threads == 1 ? " thread" : " threads") << ", "
                      << rt::interrupt::tokens_held() << " jobserver tokens\n";
        return run(cl, threads);
    } catch (const LateUsageError& e) {
        std::cerr << "rt: " << rt::printable_message(e.message)
                  << "\nTry 'rt --help' for more information.\n";
        return kExitUsage;
    } catch (const rt::Error& e) {
        std::cerr << rt::printable_message(e.what()) << "\n";
    } catch (const std::bad_alloc&) {
        std::cerr << "rt: out of memory\n";
    } catch (const std::system_error& e) {
        // std::thread's way to say the system would not start another thread.
        if (e.code() == std::errc::resource_unavailable_try_again)
            std::cerr << "rt: cannot start another thread (" << rt::printable_message(e.what())
                      << "): try a smaller -j\n";
        else
            std::cerr << "rt: " << rt::printable_message(e.what()) << "\n";
    } catch (const std::exception& e) {
        std::cerr << "rt: " << rt::printable_message(e.what()) << "\n";
    }
    return kExitError;
}
