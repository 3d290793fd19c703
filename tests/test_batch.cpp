// Batch use: --size, progress, --stats and -q, through the library and the real binary.
#include <string>

#include "batch/progress.h"
#include "batch/statistics.h"
#include "check.h"
#include "cli_util.h"
#include "rt/render.h"
#include "rt/viewer.h"
#include "scene_util.h"

using namespace rt_test;

namespace {

// A small scene whose viewer's x and y vectors are 4 : 3, rendered at 40 x 30.
std::string scene_at(int xres, int yres) {
    return "102  0 0 5  0 0 0  0.4 0 0  0 0.3 0  " + std::to_string(xres) + " " +
           std::to_string(yres) +
           "\n101 2 3 4  20 20 20\n103 0.1 0.1 0.1\n"
           "1 1  0 0 0  100 0.8 0.3 0.2  0.3 20 0.6 0.2 1.5\n"
           "2 -1  0 1 0  100 0.6 0.6 0.6  0.5 10 0.5 0 1\n";
}

// The numbers of a binary PPM's header: width and height.
std::pair<int, int> ppm_size(const std::string& bytes) {
    std::istringstream in(bytes);
    std::string magic;
    int w = 0, h = 0;
    in >> magic >> w >> h;
    return {w, h};
}

int count_lines_starting(const std::string& text, const std::string& prefix) {
    int n = 0;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (line.rfind(prefix, 0) == 0) ++n;
    return n;
}

}  // namespace

TEST(size_renders_exactly_what_the_viewer_at_that_resolution_renders) {
    const auto dir = work_dir("size");
    write_file(dir / "scene.in", scene_at(40, 30));
    write_file(dir / "big.in", scene_at(80, 60));
    const RunResult resized = run_rt(dir, "scene.in --no-metadata --size 80x60 -o resized.ppm");
    CHECK_EQ(resized.status, 0);
    CHECK_EQ(resized.err, "");  // the same 4 : 3 shape: no warning
    const RunResult direct = run_rt(dir, "big.in --no-metadata -o direct.ppm");
    CHECK_EQ(direct.status, 0);
    const std::string a = read_file(dir / "resized.ppm"), b = read_file(dir / "direct.ppm");
    CHECK(ppm_size(a) == std::make_pair(80, 60));
    CHECK(a == b);
    // -r reports the size given.
    CHECK_CONTAINS(run_rt(dir, "-r scene.in --size 12x9").out, "12x9");
}

TEST(size_warns_when_pixels_stop_being_square) {
    const auto dir = work_dir("size-warning");
    write_file(dir / "scene.in", scene_at(40, 30));
    const RunResult wide = run_rt(dir, "scene.in --no-metadata --size 60x30 -o out.ppm");
    CHECK_EQ(wide.status, 0);
    CHECK_CONTAINS(wide.err, "rt: warning: --size 60x30 gives non-square pixels");
    CHECK_CONTAINS(wide.err, "use --size 60x45");
    CHECK(ppm_size(read_file(dir / "out.ppm")) == std::make_pair(60, 30));
    // -q keeps stderr for errors only.
    CHECK_EQ(run_rt(dir, "-q scene.in --size 60x30 -o out.ppm").err, "");
    // A scene whose own pixels are not square keeps their shape without a warning.
    write_file(dir / "odd.in", scene_at(40, 40));
    CHECK_EQ(run_rt(dir, "odd.in --size 20x20 -o out.ppm").err, "");
}

TEST(size_usage_errors) {
    const auto dir = work_dir("size-errors");
    write_file(dir / "scene.in", scene_at(40, 30));
    for (const char* bad : {"0x10", "10x0", "10", "x10", "10x", "axb", "10x10x10", "-5x10",
                            "16385x1", "16384x16384", "99999999999x1"}) {
        const RunResult r = run_rt(dir, std::string("scene.in -o out.ppm --size ") + bad);
        CHECK_EQ(r.status, 2);
        CHECK_CONTAINS(r.err, "--size");
    }
    CHECK(!std::filesystem::exists(dir / "out.ppm"));
}

TEST(square_pixel_height_by_hand) {
    rt::Viewer v;
    v.x = {0.4, 0, 0};
    v.y = {0, 0.3, 0};
    v.xres = 400;
    v.yres = 300;
    CHECK(!rt::square_pixel_height(v).has_value());
    v.xres = 401;  // 300.75 rounds to 301: as square as whole pixels allow
    v.yres = 301;
    CHECK(!rt::square_pixel_height(v).has_value());
    v.xres = 400;
    v.yres = 400;
    CHECK(rt::square_pixel_height(v) == 300);
}

TEST(stats_lines_and_the_same_image) {
    const auto dir = work_dir("stats");
    write_file(dir / "scene.in", scene_at(40, 30));
    const RunResult with = run_rt(dir, "scene.in --stats -o with.ppm");
    const RunResult without = run_rt(dir, "scene.in -o without.ppm");
    CHECK_EQ(with.status, 0);
    CHECK(read_file(dir / "with.ppm") == read_file(dir / "without.ppm"));
    CHECK_EQ(count_lines_starting(with.err, "rt: stats: "), 4);
    CHECK_CONTAINS(with.err, "rt: stats: time: read ");
    CHECK_CONTAINS(with.err, "rays: 1200 primary, ");
    CHECK_CONTAINS(with.err, "object intersection tests");
    CHECK_CONTAINS(with.err, "2 objects, 1 light; ");
    CHECK_EQ(without.err, "");
}

TEST(progress_lines_only_when_asked_when_stderr_is_not_a_terminal) {
    const auto dir = work_dir("progress");
    write_file(dir / "scene.in", scene_at(40, 30));
    CHECK_EQ(run_rt(dir, "scene.in -o out.ppm").err, "");
    const RunResult asked = run_rt(dir, "scene.in --progress -o out.ppm");
    CHECK_EQ(asked.status, 0);
    // Each line names the image, so that lines of several renders in one log can be told apart.
    CHECK_CONTAINS(asked.err, "rt: out.ppm: 100%");
    CHECK_CONTAINS(run_rt(dir, "scene.in --progress > out.ppm").err, "rt: scene.in: 100%");
    CHECK_CONTAINS(asked.err, "Mrays/s");
    CHECK(asked.err.find('\r') == std::string::npos);  // plain lines for logs
    CHECK_EQ(run_rt(dir, "scene.in --progress -q -o out.ppm").err, "");
}

// -q silences warnings, notes and progress, but not what was asked for by name: -q --stats
// prints the statistics alone (docs/cli.md says so).
TEST(quiet_keeps_the_statistics_that_were_asked_for) {
    const auto dir = work_dir("quiet_stats");
    write_file(dir / "scene.in", scene_at(40, 30));
    const RunResult r = run_rt(dir, "-q --stats --progress --size 60x30 scene.in -o out.ppm");
    CHECK_EQ(r.status, 0);
    CHECK_CONTAINS(r.err, "rt: stats: time: ");
    CHECK_CONTAINS(r.err, "rt: stats: rays: ");
    CHECK(r.err.find("warning") == std::string::npos);  // --size 60x30 would warn of its pixels
    CHECK(r.err.find("%") == std::string::npos);        // no progress line
    std::size_t lines = 0;
    for (const char c : r.err) lines += c == '\n' ? 1 : 0;
    CHECK_EQ(lines, 4u);
}

TEST(progress_formatting_by_hand) {
    CHECK_EQ(rt::format_duration(0), "0:00");
    CHECK_EQ(rt::format_duration(65.4), "1:05");
    CHECK_EQ(rt::format_duration(3 * 3600 + 2 * 60 + 9), "3:02:09");
    // 25 % done after 10 s: 30 s left.
    CHECK_EQ(rt::format_progress(0.25, 12.34e6, 10), " 25%  12.3 Mrays/s  0:10 elapsed  0:30 left");
    CHECK_EQ(rt::format_progress(1, 1e6, 62), "100%  1.0 Mrays/s  1:02 elapsed");
    CHECK_EQ(rt::format_progress(0, 0, 0), "  0%  0.0 Mrays/s  0:00 elapsed");
    // Resumed: 60 % came from a checkpoint, 20 % more took 10 s, so the last 20 % take 10 s;
    // nothing is estimated before this run has done anything.
    CHECK_EQ(rt::format_progress(0.8, 1e6, 10, 0.6), " 80%  1.0 Mrays/s  0:10 elapsed  0:10 left");
    CHECK_EQ(rt::format_progress(0.6, 0, 1, 0.6), " 60%  0.0 Mrays/s  0:01 elapsed");
}

TEST(render_publishes_every_row_and_ray) {
    const rt::Scene scene = parse_scene(scene_at(40, 30));
    for (const bool adaptive : {false, true}) {
        rt::RenderOptions options;
        if (adaptive) options.adaptive_threshold = 0.05;
        rt::RenderStats stats;
        rt::RenderProgress progress;
        rt::render(scene, options, &stats, &progress);
        CHECK_EQ(progress.rows_done.load(), progress.rows_total.load());
        CHECK_EQ(progress.rows_total.load(), adaptive ? 60u : 30u);
        CHECK_EQ(progress.rays.load(), stats.total());
    }
}

TEST(rays_are_counted_by_kind) {
    // A mirror wall filling the view: every primary ray makes one reflected ray, which
    // escapes. No lights: no shadow rays.
    const std::string mirror =
        "102  0 0 5  0 0 0  0.4 0 0  0 0.3 0  8 6\n"
        "2 0  0 0 1  100 1 1 1  1 1 0 0 1\n";
    rt::RenderStats stats;
    rt::render(parse_scene(mirror), {}, &stats);
    CHECK_EQ(stats.primary_rays, 48u);
    CHECK_EQ(stats.reflected_rays, 48u);
    CHECK_EQ(stats.refracted_rays, 0u);
    CHECK_EQ(stats.shadow_rays, 0u);
    // A clear pane instead (kt 1, ks 0): one refracted ray each.
    const std::string pane =
        "102  0 0 5  0 0 0  0.4 0 0  0 0.3 0  8 6\n"
        "2 0  0 0 1  100 1 1 1  0 1 0 1 1\n";
    rt::RenderStats through;
    rt::RenderOptions linear;
    linear.accelerate = false;
    rt::render(parse_scene(pane), linear, &through);
    CHECK_EQ(through.refracted_rays, 48u);
    CHECK_EQ(through.reflected_rays, 0u);
    // The linear scan asks every object (one here) for every ray.
    CHECK_EQ(through.object_tests, through.total());
}

TEST(statistics_format) {
    rt::RunStatistics s;
    s.times = {0.5, 0.25, 2, 0.125};
    s.rays.primary_rays = 100;
    s.rays.reflected_rays = 20;
    s.rays.refracted_rays = 30;
    s.rays.shadow_rays = 50;
    s.rays.object_tests = 800;
    s.threads = 2;
    s.objects = 7;
    s.lights = 3;
    s.peak_memory_bytes = 3 * 1024 * 1024;
    CHECK_EQ(rt::format_statistics(s),
             "rt: stats: time: read 0.500 s, build 0.250 s, render 2.000 s, write 0.125 s\n"
             "rt: stats: rays: 100 primary, 20 reflected, 30 refracted, 50 shadow; 200 in all, "
             "0.00 M/s\n"
             "rt: stats: tests: 800 object intersection tests, 4.00 per ray\n"
             "rt: stats: scene: 7 objects, 3 lights; 2 threads; peak memory 3.0 MiB\n");
    CHECK(rt::peak_memory_bytes() > 0);
}
