// The fuzz cases of every input surface besides the scene reader (tests/fuzz/fuzz_cases.h),
// run in ctest with any compiler: every input in tests/fuzz/surfaces/ (the findings of issue
// 21's campaign and seeds), then seeded mutations of the seeds, so that what the libFuzzer
// targets check is checked on every build, in about a second.
#include <filesystem>
#include <string>
#include <vector>

#include "check.h"
#include "cli_util.h"
#include "fuzz/fuzz_cases.h"
#include "image/deflate.h"

namespace fs = std::filesystem;
using rt_test::read_file;

namespace {

// A small deterministic generator (SplitMix64), so every run mutates alike.
class Mutator {
  public:
    explicit Mutator(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(next() % n); }

    // One to four byte-level changes: flip, set, insert, delete, or copy a run elsewhere.
    std::string mutate(std::string s) {
        const int changes = 1 + static_cast<int>(below(4));
        for (int i = 0; i < changes; ++i) {
            const std::size_t at = below(s.size() + 1);
            switch (below(5)) {
                case 0:
                    if (at < s.size()) s[at] = static_cast<char>(s[at] ^ (1 << below(8)));
                    break;
                case 1:
                    if (at < s.size()) s[at] = static_cast<char>(below(256));
                    break;
                case 2:
                    s.insert(at, 1, static_cast<char>(below(256)));
                    break;
                case 3:
                    if (at < s.size()) s.erase(at, 1 + below(8));
                    break;
                default: {
                    const std::size_t from = below(s.size() + 1);
                    const std::string run = s.substr(from, 1 + below(16));
                    s.insert(at, run);
                }
            }
        }
        return s;
    }

  private:
    std::uint64_t state_;
};

std::vector<std::string> inputs_in(const fs::path& dir) {
    std::vector<std::string> inputs;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.is_regular_file()) inputs.push_back(read_file(entry.path()));
    return inputs;
}

const fs::path kSurfaces = fs::path(RT_SOURCE_DIR) / "tests/fuzz/surfaces";

// Runs every input of a surface's directory, then `mutations` mutations of them (and of any
// extra seeds), through the case; every problem is reported with the input's size.
template <typename Case>
void run_surface(const char* surface, Case check, std::vector<std::string> seeds, int mutations) {
    const std::vector<std::string> found = inputs_in(kSurfaces / surface);
    CHECK(!found.empty());
    int problems = 0;
    for (const std::string& input : found) {
        const std::string problem = check(input);
        if (!problem.empty()) ++problems;
        CHECK_EQ(problem, std::string());
    }
    seeds.insert(seeds.end(), found.begin(), found.end());
    Mutator mutator(21);
    for (int i = 0; i < mutations; ++i) {
        const std::string& seed = seeds[static_cast<std::size_t>(i) % seeds.size()];
        if (seed.size() > 20000) continue;  // the large findings are run as they are only
        const std::string problem = check(mutator.mutate(seed));
        if (!problem.empty() && problems++ < 5) CHECK_EQ(problem, std::string());
    }
    CHECK_EQ(problems, 0);
}

}  // namespace

TEST(rtpp_sources_and_their_mutations) {
    std::vector<std::string> seeds;
    for (const auto& entry : fs::directory_iterator(fs::path(RT_SOURCE_DIR) / "scenes"))
        if (entry.path().extension() == ".rts") seeds.push_back(read_file(entry.path()));
    CHECK(seeds.size() > 10);
    run_surface("rtpp", rt_fuzz::rtpp_case, seeds, 3000);
}

TEST(images_and_their_mutations) {
    // Small images of every kind the decoder reads, written by the encoders.
    rt::ImageMetadata m;
    m.set("Software", "rt");
    m.set("Caf\xc3\xa9", "cr\xc3\xa8me");
    const rt::SampleImage rgb{
        3, 2, 3, 8, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18}};
    const rt::SampleImage grey16{2, 2, 1, 16, {0, 1, 2, 3, 4, 5, 255, 255}};
    const rt::SampleImage rgba{1, 2, 4, 8, {1, 2, 3, 4, 5, 6, 7, 8}};
    rt::ImageMetadata ppm_metadata;
    ppm_metadata.set("Software", "rt");
    const std::vector<std::string> seeds = {
        rt::encode_png(rgb, m),
        rt::encode_png(grey16, {}),
        rt::encode_png(rgba, m),
        rt::encode_ppm(rgb, ppm_metadata),
        rt::encode_ppm(grey16, {}),
        rt::encode_ppm_plain(rgb, ppm_metadata),
        rt::encode_pfm(rt::to_raster(rt::decode_image(rt::encode_png(rgb, {}))))};
    run_surface("image", rt_fuzz::image_case, seeds, 3000);
}

TEST(inflate_streams_and_their_mutations) {
    const std::vector<std::string> seeds = {rt::deflate("abcabcabcabc hello hello hello"),
                                            rt::deflate(std::string(1000, 'x')), rt::deflate("")};
    run_surface("inflate", rt_fuzz::inflate_case, seeds, 3000);
}

TEST(nff_and_its_mutations) { run_surface("nff", rt_fuzz::nff_case, {}, 2000); }

TEST(meshes_and_their_mutations) { run_surface("mesh", rt_fuzz::mesh_case, {}, 2000); }

namespace {

// The structured cases read any bytes as choices, so the seeds (surfaces/png, merge and
// checkpoint) and their mutations are all files the case builds; plus bytes from the
// generator, for choices no seed makes.
std::vector<std::string> generated_choices(std::uint64_t seed, int count) {
    Mutator mutator(seed);
    std::vector<std::string> out;
    for (int i = 0; i < count; ++i) {
        std::string bytes(1 + mutator.below(2000), '\0');
        for (char& c : bytes) c = static_cast<char>(mutator.below(256));
        out.push_back(bytes);
    }
    return out;
}

}  // namespace

TEST(structured_pngs_and_their_mutations) {
    run_surface("png", rt_fuzz::png_case, generated_choices(15948, 200), 3000);
}

TEST(merges_and_their_mutations) {
    run_surface("merge", rt_fuzz::merge_case, generated_choices(19, 200), 3000);
}

TEST(checkpoints_and_their_mutations) {
    run_surface("checkpoint", rt_fuzz::checkpoint_case, generated_choices(15, 200), 3000);
}
