// Every readable scene scenes/X.rts compiles to the same scene as its numeric twin
// scenes/X.in, so rt renders them byte for byte alike. The numbers are compared first (the
// same numbers in the same order are the same scene, and a difference is shown at its
// place); a pair whose numbers differ must still render to the same bytes.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "check.h"
#include "cli_util.h"
#include "rt/image_io.h"
#include "rt/reader.h"
#include "rt/render.h"
#include "rtpp/compiler.h"
#include "scene/lexer.h"

namespace fs = std::filesystem;

namespace {

const fs::path kScenes = fs::path(RT_SOURCE_DIR) / "scenes";

struct Word {
    std::string text;  // a number's value printed exactly, or a path resolved
    std::string place;
};

// The scene's tokens as values: numbers by their exact double, paths resolved.
std::vector<Word> words(const std::string& text, const std::string& name) {
    std::istringstream in(text);
    rt::Lexer lexer(in, name);
    std::vector<Word> result;
    for (;;) {
        const rt::Token& token = lexer.next();
        if (token.at_end()) return result;
        Word word;
        word.place = lexer.place(token.where);
        const std::string spelled(token.text);  // strtod needs the terminating NUL
        char* end = nullptr;
        const double value = std::strtod(spelled.c_str(), &end);
        if (!token.quoted && end != spelled.c_str() && *end == '\0') {
            char exact[40];
            std::snprintf(exact, sizeof exact, "%.17g", value);
            word.text = exact;
        } else {
            const fs::path p(spelled);
            word.text = (p.is_absolute() ? p : kScenes / p).lexically_normal().string();
        }
        result.push_back(std::move(word));
    }
}

std::string render(const std::string& text, const std::string& name) {
    std::istringstream in(text);
    const rt::Scene scene = rt::read_scene(in, name, kScenes);
    std::ostringstream out;
    out << rt::encode_image(rt::render(scene, {}), {});
    return out.str();
}

std::string read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST(every_numeric_scene_has_a_readable_twin) {
    for (const auto& entry : fs::directory_iterator(kScenes)) {
        if (entry.path().extension() != ".in") continue;
        fs::path rts = entry.path();
        rts.replace_extension(".rts");
        if (!fs::exists(rts))
            rt_test::record_failure(__FILE__, __LINE__, rt_test::join(rts, " is missing"));
    }
}

TEST(every_readable_scene_renders_as_its_numeric_twin) {
    const std::vector<fs::path> files = rt_test::files_with_extension(kScenes, ".rts");
    CHECK(files.size() >= 30);
    for (const fs::path& rts : files) {
        fs::path in = rts;
        in.replace_extension(".in");
        if (!fs::exists(in)) continue;
        std::string compiled;
        try {
            compiled = rtpp::compile_file(rts.string());
        } catch (const std::exception& e) {
            rt_test::record_failure(__FILE__, __LINE__, e.what());
            continue;
        }
        const std::string numeric = read(in);
        const auto a = words(compiled, rts.string());
        const auto b = words(numeric, in.string());
        std::size_t i = 0;
        while (i < a.size() && i < b.size() && a[i].text == b[i].text) ++i;
        if (i == a.size() && i == b.size()) {
            std::cout << "  " << rts.filename().string() << ": the same " << a.size()
                      << " numbers\n";
            continue;
        }
        // Not the same numbers: the images must still be the same bytes.
        const bool same_image = render(compiled, rts.string()) == render(numeric, in.string());
        std::cout << "  " << rts.filename().string() << ": numbers differ at "
                  << (i < a.size() ? a[i].place + " (" + a[i].text + ")" : "the end") << " vs "
                  << (i < b.size() ? b[i].place + " (" + b[i].text + ")" : "the end")
                  << (same_image ? "; the images are the same bytes\n" : "\n");
        if (!same_image)
            rt_test::record_failure(__FILE__, __LINE__,
                                    rt_test::join(rts, " renders differently from ", in));
    }
}
