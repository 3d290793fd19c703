// rtpp's bounds against the hostile sources of issue 21's campaign: every way of building
// depth (operator chains, else-if chains, objects named inside objects) is held to the
// nesting limit, so nothing recurses without bound, freeing included; every object written
// counts, a CSG's operands too; and an include is read only from a regular file, never
// blocking.
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <string>

#include "check.h"
#include "cli_util.h"
#include "rtpp/compiler.h"
#include "rtpp_util.h"

namespace fs = std::filesystem;
using rt_test::write_file;
using rtpp_test::error_of;
using rtpp_test::file_error_of;
using rtpp_test::kCamera;

namespace {

// "first op first op ... first", n operands.
std::string chain(const std::string& first, const std::string& op, int n) {
    std::string text = first;
    for (int i = 1; i < n; ++i) text += op + first;
    return text;
}

}  // namespace

TEST(operator_chains_count_towards_the_nesting_limit) {
    // Finding 1: 10,000 terms overflowed the stack while being evaluated.
    for (const char* op : {"+", "*", " and ", " or ", "-", "/"}) {
        const std::string e = error_of(kCamera + "let a = " + chain("1", op, 10000));
        CHECK_CONTAINS(e, "t.rts:2:");
        CHECK_CONTAINS(e,
                       "nested more than 200 deep (blocks, parentheses, objects and "
                       "operators count)");
    }
    CHECK_CONTAINS(error_of(kCamera + "let a = <1, 2, 3>" + chain(".x", "", 10000)),
                   "nested more than 200 deep");
    // A chain never evaluated crashed while it was freed: it is refused as it is parsed.
    CHECK_CONTAINS(error_of(kCamera + "if 0 { let a = " + chain("1", "+", 300000) + " }"),
                   "nested more than 200 deep");
    // The limit means the same for each way of nesting: with 20, under a let (one level), a
    // chain of 19 terms (18 operators) is the longest that compiles, as 19 parentheses are the
    // most.
    rtpp::CompileOptions small;
    small.limits.nesting = 20;
    CHECK_EQ(error_of(kCamera + "let a = " + chain("1", "+", 19) + "\nambient { intensity a / 19 }",
                      small),
             std::string());
    CHECK_CONTAINS(error_of(kCamera + "let a = " + chain("1", "+", 20), small),
                   "t.rts:2:46: nested more than 20 deep");
    CHECK_EQ(
        error_of(kCamera + "let a = " + std::string(19, '(') + "1" + std::string(19, ')'), small),
        std::string());
    CHECK_CONTAINS(
        error_of(kCamera + "let a = " + std::string(20, '(') + "1" + std::string(20, ')'), small),
        "nested more than 20 deep");
    // A chain inside parentheses counts both.
    CHECK_CONTAINS(error_of(kCamera + "let a = ((((" + chain("1", "+", 16) + "))))", small),
                   "nested more than 20 deep");
    // A value from a long chain within the limit is still exact.
    const std::string out = rtpp::compile(
        kCamera + "let a = " + chain("1", " + ", 150) + "\nambient { intensity a / 150 }", "t.rts",
        ".");
    CHECK_CONTAINS(out, "103 1 1 1");
}

TEST(else_if_chains_count_towards_the_nesting_limit) {
    std::string source = kCamera + "if 0 { }";
    for (int i = 0; i < 5000; ++i) source += " else if 0 { }";
    CHECK_CONTAINS(error_of(source), "nested more than 200 deep");
    rtpp::CompileOptions small;
    small.limits.nesting = 20;
    std::string ok = kCamera + "if 0 { }";
    for (int i = 0; i < 18; ++i) ok += " else if 0 { }";
    CHECK_EQ(error_of(ok + " else { }", small), std::string());
    CHECK_CONTAINS(error_of(ok + " else if 0 { } else if 0 { }", small),
                   "nested more than 20 deep");
}

TEST(objects_named_inside_objects_count_towards_the_nesting_limit) {
    // Each name holds the one before: the values nest as deep as the lines go, and writing and
    // freeing them recursed as deep.
    std::string source = kCamera + "let g0 = sphere { radius 1 surface { colour 1 kd 1 } }\n";
    for (int i = 1; i <= 100000; ++i)
        source += rt_test::join("let g", i, " = group { g", i - 1, " {} }\n");
    const std::string e = error_of(source);
    CHECK_CONTAINS(e, "t.rts:202:12: objects nested more than 200 deep");
    std::string ok = kCamera + "let g0 = sphere { radius 1 surface { colour 1 kd 1 } }\n";
    for (int i = 1; i < 200; ++i) ok += rt_test::join("let g", i, " = group { g", i - 1, " {} }\n");
    CHECK_CONTAINS(rtpp::compile(ok + "g199 {}\n", "t.rts", "."), "\n1 1 0 0 0 100 1 1 1");
}

TEST(every_object_written_counts_csg_operands_included) {
    // Finding 2: doubling a union 24 times wrote 16.7 M spheres (1 GB) despite the limit; it is
    // now refused before anything is written, at once.
    std::string source = kCamera +
                         "let g1 = union { sphere { radius 1 surface { colour 1 kd 1 } }\n"
                         "  sphere { radius 1 centre <1, 0, 0> surface { colour 1 kd 1 } } }\n";
    for (int i = 2; i <= 30; ++i)
        source += rt_test::join("let g", i, " = union { g", i - 1, " {} g", i - 1, " {} }\n");
    const auto start = std::chrono::steady_clock::now();
    CHECK_CONTAINS(error_of(source + "g24 {}\n"), "t.rts:33:1: more than 10000000 objects written");
    CHECK_CONTAINS(error_of(source + "g30 {}\n"), "more than 10000000 objects written");
    CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(20));
    // 2^23 spheres fit under the limit: counted, not written here (8 M spheres take a while).
    // With a small limit: a union of three counts three, in a group or on its own.
    rtpp::CompileOptions small;
    small.limits.objects = 10;
    const std::string three =
        "let u = union { sphere { radius 1 surface { colour 1 kd 1 } }\n"
        "  sphere { radius 1 surface { colour 1 kd 1 } } sphere { radius 1 surface { colour 1 kd "
        "1 } } }\n";
    CHECK_EQ(error_of(kCamera + three + "u {} u {} group { u {} }\n", small), std::string());
    CHECK_CONTAINS(
        error_of(kCamera + three + "u {} u {} group { u {} ambient { intensity 1 } }\n", small),
        "t.rts:4:11: more than 10 objects written");
}

TEST(an_include_reads_only_a_regular_file_and_never_blocks) {
    // Finding 13: an include of a FIFO without a writer hung for ever.
    const fs::path dir = rt_test::work_dir("rtpp-include-fifo");
    const fs::path fifo = dir / "fifo";
    fs::remove(fifo);
    CHECK_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    write_file(dir / "s.rts", kCamera + "include \"fifo\"\n");
    CHECK_CONTAINS(
        file_error_of((dir / "s.rts").string()),
        "s.rts:2:1: included file '" + fifo.string() + "' is not a regular file (a FIFO)");
    write_file(dir / "d.rts", kCamera + "include \"/dev/null\"\n");
    CHECK_CONTAINS(file_error_of((dir / "d.rts").string()),
                   "d.rts:2:1: included file '/dev/null' is not a regular file (a character "
                   "device)");
    // A directory is passed over for the next candidate, as before.
    fs::create_directories(dir / "sub" / "part.rts");
    fs::create_directories(dir / "inc");
    write_file(dir / "inc" / "part.rts", "ambient { intensity 0.5 }\n");
    write_file(dir / "sub" / "s.rts", kCamera + "include \"part.rts\"\n");
    rtpp::CompileOptions options;
    options.include_dirs.push_back(dir / "inc");
    CHECK_CONTAINS(rtpp::compile_file((dir / "sub" / "s.rts").string(), options),
                   "103 0.5 0.5 0.5");
}
