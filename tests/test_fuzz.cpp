// A deterministic fuzz test, run by ctest with any compiler: seeded random token soups of every
// ID and extreme numbers, and mutations of the example scenes, each read and (if it reads)
// rendered at 3 x 3 pixels. No case may crash, throw anything but an rt::Error with a place,
// or take long. The long campaign is the libFuzzer target (tests/fuzz/README.md).
#include <chrono>
#include <filesystem>
#include <vector>

#include "check.h"
#include "cli_util.h"
#include "fuzz/fuzz_one.h"

using namespace rt_test;
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kIds = {
    "1",   "2",   "3",   "4",   "5",   "6",   "7",   "8",   "9",   "10",  "11",  "12",  "13",
    "14",  "20",  "21",  "22",  "100", "101", "102", "103", "104", "105", "106", "107", "108",
    "109", "110", "111", "112", "113", "114", "0",   "15",  "99",  "115", "-1",  "1e10"};
const std::vector<std::string> kNumbers = {"0",         "-0",     "1",
                                           "-1",        "0.5",    "2",
                                           "3",         "4096",   "4097",
                                           "1e-162",    "1e-320", "4.9e-324",
                                           "1e-400",    "1e308",  "-1e308",
                                           "1e999",     "1e10",   "2147483648",
                                           "1e100",     "nan",    "inf",
                                           "0x1p-1074", "16384",  "16385",
                                           "3.5",       "-2.5",   "1.0000000000000002",
                                           "64"};
const std::vector<std::string> kOddTokens = {"\"textures/letter-f.ppm\"",
                                             "textures/letter-f.ppm",
                                             "\"\"",
                                             "\"unterminated",
                                             "x",
                                             std::string("1\0x", 3),
                                             "\x1b[2J",
                                             "#line 9 \"m.rts\"\n",
                                             "# comment\n",
                                             "\n",
                                             "\xff",
                                             std::string(5000, '7')};

std::string pick(Random& random, const std::vector<std::string>& from) {
    return from[random.next() % from.size()];
}

std::string number(Random& random) {
    if (random.next() % 3 == 0) return pick(random, kNumbers);
    return std::to_string(static_cast<double>(random.next() % 2001) / 100.0 - 10.0);
}

// A viewer that reads, then IDs, each with a random count of numbers and now and then an odd
// token: most cases fail somewhere inside an object, at every kind of field.
std::string token_soup(Random& random) {
    std::string text = "102 0 0 5 0 0 0 1 0 0 0 1 0 3 3\n";
    const int objects = 1 + static_cast<int>(random.next() % 8);
    for (int o = 0; o < objects; ++o) {
        text += pick(random, kIds);
        const int count = static_cast<int>(random.next() % 24);
        for (int i = 0; i < count; ++i) {
            const auto kind = random.next() % 20;
            text += ' ';
            text += kind == 0  ? pick(random, kOddTokens)
                    : kind < 4 ? pick(random, kIds)
                               : number(random);
        }
        text += '\n';
    }
    return text;
}

// Splits at whitespace into tokens, keeping each token's start.
std::vector<std::size_t> token_starts(const std::string& text) {
    std::vector<std::size_t> starts;
    for (std::size_t i = 0; i < text.size(); ++i)
        if (text[i] > ' ' && (i == 0 || text[i - 1] <= ' ')) starts.push_back(i);
    return starts;
}

std::string mutate(Random& random, std::string text) {
    const int mutations = 1 + static_cast<int>(random.next() % 4);
    for (int m = 0; m < mutations && !text.empty(); ++m) {
        const auto starts = token_starts(text);
        if (starts.empty()) break;
        const std::size_t at = starts[random.next() % starts.size()];
        const std::size_t end = std::min(text.find_first_of(" \t\r\n", at), text.size());
        switch (random.next() % 7) {
            case 0:  // a token becomes an extreme number
                text.replace(at, end - at, pick(random, kNumbers));
                break;
            case 1:  // a token is lost
                text.erase(at, end - at);
                break;
            case 2:  // a token is doubled
                text.insert(at, text.substr(at, end - at) + " ");
                break;
            case 3:  // an ID appears
                text.insert(at, pick(random, kIds) + " ");
                break;
            case 4:  // a byte changes
                text[random.next() % text.size()] = static_cast<char>(random.next() % 256);
                break;
            case 5:  // the file ends early
                text.resize(random.next() % text.size());
                break;
            default:  // an odd token appears
                text.insert(at, pick(random, kOddTokens) + " ");
                break;
        }
    }
    return text;
}

struct Tally {
    int cases = 0, read = 0, errors = 0;
    double slowest = 0;
};

void run_case(const std::string& text, Tally& tally) {
    const auto start = std::chrono::steady_clock::now();
    rt_fuzz::Outcome outcome;
    try {
        outcome = rt_fuzz::fuzz_one(text, fs::path(RT_SOURCE_DIR) / "scenes");
    } catch (const std::exception& e) {
        record_failure(__FILE__, __LINE__, join("not an rt::Error: ", e.what(), " for ", text));
        return;
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++tally.cases;
    tally.slowest = std::max(tally.slowest, seconds);
    // Generous: a case takes milliseconds, but sanitizers and a busy machine slow it down.
    if (seconds > 10) record_failure(__FILE__, __LINE__, join("took ", seconds, " s: ", text));
    if (outcome.read) {
        ++tally.read;
    } else {
        ++tally.errors;
        if (!outcome.placed)
            record_failure(__FILE__, __LINE__, join("error without a place: ", outcome.error));
    }
}

}  // namespace

TEST(random_token_soups) {
    Random random(11);
    Tally tally;
    for (int i = 0; i < 10000; ++i) run_case(token_soup(random), tally);
    CHECK_EQ(tally.cases, 10000);
    CHECK(tally.errors > 5000);  // it does reach errors of every kind...
    std::printf("token soups: %d cases, %d read, %d errors, slowest %.3f s\n", tally.cases,
                tally.read, tally.errors, tally.slowest);
}

TEST(mutated_example_scenes) {
    std::vector<std::string> scenes;
    for (const auto& entry : fs::directory_iterator(fs::path(RT_SOURCE_DIR) / "scenes"))
        if (entry.path().extension() == ".in" && entry.file_size() < 64 * 1024)
            scenes.push_back(read_file(entry.path()));
    CHECK(scenes.size() > 10);
    Random random(29);
    Tally tally;
    for (int i = 0; i < 10000; ++i) run_case(mutate(random, scenes[i % scenes.size()]), tally);
    CHECK(tally.read > 500);  // ... and past them, into the renderer
    std::printf("mutated scenes: %d cases, %d read, %d errors, slowest %.3f s\n", tally.cases,
                tally.read, tally.errors, tally.slowest);
}

TEST(what_the_campaigns_found) {
    // Inputs libFuzzer found (tests/fuzz/regressions), kept so each finding stays fixed.
    Tally tally;
    for (const auto& entry :
         fs::directory_iterator(fs::path(RT_SOURCE_DIR) / "tests/fuzz/regressions"))
        run_case(read_file(entry.path()), tally);
    CHECK(tally.cases >= 1);
}

TEST(a_render_that_tests_every_triangle_is_only_read) {
    // The reader campaign's timeout (regressions/reader-far-rays-through-meshes.in): twelve
    // vases seen from 4.4e26 away, 8 lights. Read, counted, and not rendered by the harness.
    const std::string text = read_file(fs::path(RT_SOURCE_DIR) /
                                       "tests/fuzz/regressions/reader-far-rays-through-meshes.in");
    std::istringstream in(text);
    const rt::Scene scene = rt::read_scene(in, "far.in", fs::path(RT_SOURCE_DIR) / "scenes", 1);
    CHECK_EQ(scene.objects.size(), 13u);
    CHECK_EQ(scene.mesh_triangles % 12, 0u);
    CHECK(scene.mesh_triangles / 12 > 1900);  // the vase's 1968 faces, less any of zero area
    CHECK(!rt_fuzz::cheap_to_render(scene));
    // One vase and one light: 9 pixels x 5 rays x 2 x 1968 triangles, rendered.
    std::istringstream one(
        "102 0 0 5 0 0 0 1 0 0 0 1 0 3 3\n104 4 3 2 1 1 1\n"
        "15 2 \"models/vase.ply\" 100 0.2 0.45 0.7 0.35 80 0.65 0 1\n");
    const rt::Scene small = rt::read_scene(one, "one.in", fs::path(RT_SOURCE_DIR) / "scenes", 1);
    CHECK_EQ(small.mesh_triangles * 12, scene.mesh_triangles);
    CHECK(rt_fuzz::cheap_to_render(small));
}
