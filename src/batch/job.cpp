#include "batch/job.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "batch/checkpoint_store.h"
#include "batch/cost.h"
#include "batch/depfile.h"
#include "batch/progress.h"
#include "batch/statistics.h"
#include "common/digest.h"
#include "common/exit_status.h"
#include "common/interrupt.h"
#include "common/message_text.h"
#include "common/output_file.h"
#include "rt/error.h"
#include "rt/image_io.h"
#include "rt/reader.h"
#include "rt/render.h"

namespace rt {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// --size: the viewer's vectors stay, so the field of view does; say when pixels stop being
// square, and which size would keep them so.
void apply_size(Viewer& viewer, const ImageSize& size, bool quiet) {
    // A size in the scene's own proportions keeps its pixels' shape, square or not.
    const bool same_shape =
        std::lround(static_cast<double>(size.width) * viewer.yres / viewer.xres) == size.height ||
        std::lround(static_cast<double>(size.height) * viewer.xres / viewer.yres) == size.width;
    viewer.xres = size.width;
    viewer.yres = size.height;
    if (quiet || same_shape) return;
    if (const auto square = square_pixel_height(viewer))
        std::cerr << "rt: warning: --size " << size.width << "x" << size.height
                  << " gives non-square pixels (the viewer's x and y vectors are "
                  << format_number(length(viewer.x) / length(viewer.y))
                  << " : 1); for square pixels use --size " << size.width << "x" << *square
                  << ", or change the viewer's vectors\n";
}

// The pixels to render, once --size has set the image's size: the whole image, or --region
// when the image contains it (a usage error known only now).
PixelRect fit_command_line(const CommandLine& cl, Viewer& viewer) {
    if (cl.size) apply_size(viewer, *cl.size, cl.quiet);
    const PixelRect region = cl.region.value_or(image_rect(viewer));
    if (const auto problem = region_problem(region, viewer.xres, viewer.yres))
        throw UsageError{*problem};
    return region;
}

// -r: what was read, on standard output.
int print_summary(const CommandLine& cl, const Scene& scene) {
    std::ostringstream summary;
    const std::string name = cl.input == "-" ? "<stdin>" : show_token(cl.input, kShowWhole);
    summary << name << ": " << scene.objects.size() << " objects, " << scene.lights.size()
            << " lights, ";
    // The background is no light, but it is what lights the image where nothing is hit.
    if (const auto& b = scene.background) {
        summary << "background";
        for (std::size_t i = 0; i < kSpectrumComponents; ++i) summary << " " << (*b)[i];
        summary << ", ";
    }
    summary << scene.viewer.xres << "x" << scene.viewer.yres;
    if (const std::size_t n = scene.skipped_triangles; n != 0)
        summary << ", " << n << " zero-area " << (n == 1 ? "triangle" : "triangles") << " skipped";
    summary << "\n";
    return print_to_stdout("rt", summary.view());
}

// What the reader accepted but ignored (a mesh file's texture coordinates): worth knowing,
// not wrong.
void show_notes(const CommandLine& cl, const Scene& scene) {
    if (cl.quiet) return;
    for (const std::string& note : scene.notes)
        std::cerr << "rt: note: " << printable_message(note) << "\n";
}

// "rt scene.in > out.png": rt cannot see the name behind a redirect when it chooses the
// format, but it can say so afterwards, when standard output is a regular file whose name
// (through /proc/self/fd/1) asks for another format than the PPM it gets.
void warn_about_redirected_format(const CommandLine& cl) {
    if (cl.quiet || cl.output != "-" || cl.format_given) return;
    struct stat st {};
    if (::fstat(STDOUT_FILENO, &st) != 0 || !S_ISREG(st.st_mode)) return;
    std::error_code ec;
    const fs::path name = fs::read_symlink("/proc/self/fd/1", ec);
    if (ec) return;
    const auto format = format_from_extension(name.string());
    if (!format || *format == cl.image.format) return;
    std::string wrote = format_name(cl.image.format);
    for (char& c : wrote) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    std::cerr << "rt: warning: standard output is " << quote_token(name.string(), kShowWhole)
              << ", but rt writes " << wrote
              << " there: a redirect hides the name rt chooses the format by (use -o "
              << show_token(name.filename().string(), kShowWhole) << ", or -f "
              << format_name(*format) << ")\n";
}

void warn_about_cost(const CommandLine& cl, const Scene& scene) {
    if (cl.quiet) return;
    for (const std::string& warning : cost_warnings(scene, cl.render))
        std::cerr << "rt: warning: " << printable_message(warning) << "\n";
}

// The image file and the -M rule's file. They are checked and claimed before rendering, so a
// bad path fails fast, and are only replaced once complete. The files the render reads (the
// scene, its textures and mesh files) are never written over.
class ClaimedOutputs {
  public:
    ClaimedOutputs(const CommandLine& cl, const Viewer& viewer, const PixelRect& region,
                   const std::vector<SceneInput>& files)
        : encoding_(encoding_of(cl, viewer, region)),
          inputs_(inputs_of(cl, files)),
          image_(cl.output, inputs_) {
        if (cl.depfile.empty()) return;
        std::vector<std::string> dependencies;
        if (cl.input != "-") dependencies.push_back(cl.input);
        for (const SceneInput& file : files) dependencies.push_back(file.path.string());
        rule_ = make_rule(cl.output, dependencies);
        std::error_code ec;
        if (fs::weakly_canonical(cl.depfile, ec) == fs::weakly_canonical(cl.output, ec))
            throw Error(cl.depfile + ": -M and -o name the same file");
        depfile_.emplace(cl.depfile, inputs_, "the dependency rule");
    }

    // What the image file stores: floats (PFM), or samples, which are all a render for it
    // needs to keep.
    bool takes_samples() const { return encoding_.format != ImageFormat::pfm; }
    const ImageEncoding& encoding() const { return encoding_; }

    // Encodes and writes the image, then the rule: a rule for an image that failed would be
    // a lie.
    void write(const Raster& image, StageTimes& times) {
        write_encoded([&](const auto& sink) { encode_image_in_pieces(image, encoding_, sink); },
                      times);
    }
    void write(const SampleRaster& image, StageTimes& times) {
        write_encoded([&](const auto& sink) { encode_samples_in_pieces(image, encoding_, sink); },
                      times);
    }

    // The scene first (empty for standard input), then its textures and mesh files.
    static std::vector<InputFile> inputs_of(const CommandLine& cl,
                                            const std::vector<SceneInput>& files) {
        std::vector<InputFile> inputs{
            {cl.input == "-" ? std::string() : cl.input, "the scene file"}};
        for (const SceneInput& file : files) inputs.push_back({file.path, file.role});
        return inputs;
    }

  private:
    // `encode(sink)` hands the file's bytes to the sink in pieces.
    template <typename Encode>
    void write_encoded(const Encode& encode, StageTimes& times) {
        const auto start = Clock::now();
        encode(std::function<void(std::string_view)>(
            [&](std::string_view piece) { image_.append(piece); }));
        image_.commit();
        times.write = seconds_since(start);
        if (depfile_) depfile_->write_bytes(rule_);
    }

    static ImageEncoding encoding_of(const CommandLine& cl, const Viewer& viewer,
                                     const PixelRect& region) {
        ImageEncoding encoding = cl.image;
        encoding.metadata = image_metadata(cl);
        if (cl.region) add_region_metadata(encoding.metadata, region, viewer.xres, viewer.yres);
        return encoding;
    }
    ImageEncoding encoding_;
    std::vector<InputFile> inputs_;
    OutputFile image_;
    std::optional<OutputFile> depfile_;
    std::string rule_;
};

// What a progress line in a log names: the image, or the scene when the image goes to
// standard output.
std::string progress_label(const CommandLine& cl) {
    if (cl.output != "-") return show_token(cl.output, kShowWhole);
    return cl.input == "-" ? "<stdin>" : show_token(cl.input, kShowWhole);
}

// The name by which the checkpoint records a file the scene reads: as the scene names it
// (relative to the scene's directory) where it can, so that a moved project still resumes.
std::string recorded_name(const fs::path& path, const fs::path& scene_dir) {
    if (!scene_dir.empty()) {
        const fs::path relative = path.lexically_relative(scene_dir);
        if (!relative.empty() && *relative.begin() != "..") return relative.string();
    }
    return path.string();
}

// --checkpoint: what identifies this render (the options, and the digests of the scene and of
// every file it read), and which rows each pass renders.
CheckpointPlan checkpoint_plan(const CommandLine& cl, const Viewer& viewer, const PixelRect& region,
                               const std::vector<SceneInput>& files, Sha256& scene_digest) {
    CheckpointPlan plan;
    plan.path = cl.checkpoint;
    plan.resume = cl.resume;
    plan.quiet = cl.quiet;
    plan.header = render_identity(cl, viewer.xres, viewer.yres, region);
    plan.header.emplace_back("scene", "sha256 " + to_hex(scene_digest.finish()));
    const fs::path scene_dir =
        cl.input == "-" ? fs::current_path() : fs::path(cl.input).parent_path();
    std::size_t n = 0;
    for (const SceneInput& file : files) {
        std::string role = file.role;
        if (role.starts_with("the ")) role.erase(0, 4);
        plan.header.emplace_back("input " + std::to_string(++n),
                                 role + " " +
                                     quote_token(recorded_name(file.path, scene_dir), kShowWhole) +
                                     " sha256 " + sha256_file_hex(file.path));
    }
    plan.inputs = ClaimedOutputs::inputs_of(cl, files);
    if (cl.output != "-") plan.outputs.push_back(cl.output);
    if (!cl.depfile.empty()) plan.outputs.push_back(cl.depfile);
    plan.rows = region;
    if (cl.render.adaptive_threshold) plan.one_ray_rows = one_ray_rect(region, image_rect(viewer));
    return plan;
}

// The render, `render()`, with a progress display on standard error when it is a terminal
// or --progress asks for one (never under -q).
template <typename Render>
auto render_with_progress(const CommandLine& cl, RunStatistics& statistics,
                          RenderProgress& progress, const Render& render) {
    std::optional<ProgressDisplay> display;
    if (!cl.quiet && (cl.progress || isatty(STDERR_FILENO) != 0))
        display.emplace(progress,
                        isatty(STDERR_FILENO) != 0 ? ProgressDisplay::Style::terminal
                                                   : ProgressDisplay::Style::lines,
                        std::cerr, progress_label(cl));
    const auto start = Clock::now();
    auto image = render();
    statistics.times.render = seconds_since(start);
    if (display) display->finish();
    return image;
}

// --stats, on standard error once everything is written.
void report_statistics(RunStatistics& statistics, const Scene& scene, const RenderOptions& options,
                       const PixelRect& region) {
    statistics.threads = render_threads(options, region);
    statistics.objects = scene.objects.size();
    statistics.lights = scene.lights.size();
    statistics.peak_memory_bytes = peak_memory_bytes();
    std::cerr << format_statistics(statistics);
}

}  // namespace

int choose_threads(const CommandLine& cl, const JobserverAuth& auth,
                   std::optional<JobserverClient>& jobs) {
    const auto chosen = [&] {
        if (cl.render.threads > 0) return cl.render.threads;
        const int hardware = worker_threads(0);
        if (auth.kind == JobserverAuth::Kind::none) return hardware;
        if (auth.kind == JobserverAuth::Kind::disabled) return 1;
        jobs.emplace(auth);
        if (!jobs->usable()) {
            std::cerr << "rt: warning: " << printable_message(jobs->problem())
                      << "; rendering on 1 thread (-j N sets the number)\n";
            return 1;
        }
        return 1 + jobs->acquire(hardware - 1);
    };
    const int threads = chosen();
    if (const char* debug = std::getenv("RT_DEBUG");
        debug != nullptr && std::strstr(debug, "threads") != nullptr)
        std::cerr << "rt: " << threads << (threads == 1 ? " thread" : " threads") << ", "
                  << interrupt::tokens_held() << " jobserver tokens\n";
    return threads;
}

int run_job(const CommandLine& cl, int threads) try {
    RunStatistics statistics;
    std::vector<SceneInput> files;
    // A scene typed at a terminal: without a word rt would seem to hang.
    if (cl.input == "-" && isatty(STDIN_FILENO) != 0 && !cl.quiet)
        std::cerr << "rt: reading the scene from the terminal; end it with Ctrl-D (or give a "
                     "file: rt scene.in, rt < scene.in)\n";
    Sha256 scene_digest;
    Scene scene = read_scene_file(cl.input, threads, &statistics.times, &files,
                                  cl.checkpoint.empty() ? nullptr : &scene_digest);
    const PixelRect region = fit_command_line(cl, scene.viewer);
    show_notes(cl, scene);
    warn_about_redirected_format(cl);
    if (cl.read_only) return print_summary(cl, scene);
    warn_about_cost(cl, scene);
    ClaimedOutputs outputs(cl, scene.viewer, region, files);
    RenderOptions options = cl.render;
    options.threads = threads;
    RenderProgress progress;
    std::optional<CheckpointStore> checkpoint;
    if (!cl.checkpoint.empty())
        checkpoint.emplace(checkpoint_plan(cl, scene.viewer, region, files, scene_digest),
                           &progress);
    RowStore* const rows = checkpoint ? &*checkpoint : nullptr;
    // A PPM or PNG is rendered into its samples alone (3 or 6 bytes a pixel, not 24).
    if (outputs.takes_samples()) {
        const ImageEncoding& encoding = outputs.encoding();
        const SampleRaster image = render_with_progress(cl, statistics, progress, [&] {
            return render_region_samples(scene, options, region, encoding.bits, encoding.gamma,
                                         &statistics.rays, &progress, rows);
        });
        outputs.write(image, statistics.times);
    } else {
        const Raster image = render_with_progress(cl, statistics, progress, [&] {
            return render_region(scene, options, region, &statistics.rays, &progress, rows);
        });
        outputs.write(image, statistics.times);
    }
    if (checkpoint) {
        checkpoint->remove();
        statistics.checkpoint = true;
        statistics.rows = progress.rows_total.load();
        statistics.rows_resumed = checkpoint->rows_resumed();
    }
    if (cl.stats) report_statistics(statistics, scene, options, region);
    return kExitOk;
} catch (const std::system_error& e) {
    // std::thread's way to say the system would not start another thread.
    if (e.code() != std::errc::resource_unavailable_try_again) throw;
    throw Error("rt: cannot start another thread (" + std::string(e.what()) +
                "): try a smaller -j");
}

}  // namespace rt
