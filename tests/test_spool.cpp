// The spool rtpp translates NFF into: what goes in comes out whole and in order, from memory
// or from its temporary file; and an output file written in pieces replaces the old one only
// when committed.
#include <filesystem>
#include <ostream>
#include <string>

#include "check.h"
#include "cli_util.h"
#include "common/output_file.h"
#include "common/spool.h"

using namespace rt_test;
namespace fs = std::filesystem;

namespace {

std::string read_back(rt::Spool& spool) {
    std::string all;
    std::size_t largest = 0;
    spool.each_piece([&](std::string_view piece) {
        all += piece;
        largest = std::max(largest, piece.size());
    });
    CHECK(largest <= std::size_t{1} << 20);
    return all;
}

// Text that is different everywhere, so that a piece out of order or repeated shows.
std::string numbered_lines(int count) {
    std::string text;
    for (int i = 0; i < count; ++i)
        text += std::to_string(i) + " spheres and " + std::to_string(i * 7) + "\n";
    return text;
}

}  // namespace

TEST(text_within_the_limit_stays_in_memory) {
    rt::Spool spool(1000);
    std::ostream out(&spool);
    const std::string text = numbered_lines(30);
    CHECK(text.size() < 1000);
    out << text;
    CHECK_EQ(read_back(spool), text);
    CHECK(!spool.spilled());
}

TEST(text_beyond_the_limit_spills_to_a_file_and_comes_back_whole) {
    for (std::size_t limit :
         {std::size_t{0}, std::size_t{1}, std::size_t{4096}, std::size_t{65536}}) {
        rt::Spool spool(limit);
        std::ostream out(&spool);
        const std::string text = numbered_lines(200000);  // about 5 MB: several read pieces
        out << text.substr(0, 12345);
        for (char c : text.substr(12345, 1000)) out.put(c);
        out << text.substr(13345);
        out.flush();
        CHECK(spool.spilled());
        CHECK(read_back(spool) == text);
    }
}

TEST(nothing_written_reads_back_as_nothing) {
    rt::Spool spool(0);
    CHECK_EQ(read_back(spool), std::string());
}

TEST(a_file_written_in_pieces_is_replaced_only_when_committed) {
    const fs::path dir = work_dir("spool_output");
    write_file(dir / "out.in", "old\n");
    {
        rt::OutputFile out((dir / "out.in").string(), {}, "the output file", "rtpp");
        out.append("new ");
        out.append("scene\n");
        CHECK_EQ(read_file(dir / "out.in"), std::string("old\n"));
        out.commit();
    }
    CHECK_EQ(read_file(dir / "out.in"), std::string("new scene\n"));
    {
        rt::OutputFile out((dir / "out.in").string(), {}, "the output file", "rtpp");
        out.append("partial");
    }  // never committed: an error on the way leaves the old file
    CHECK_EQ(read_file(dir / "out.in"), std::string("new scene\n"));
    CHECK_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}
