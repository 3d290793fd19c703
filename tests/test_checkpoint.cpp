// The checkpoint file's format and the digest that identifies a render's inputs: SHA-256
// against the standard's test vectors; rows come back bit for bit; a file cut or damaged
// anywhere keeps exactly the complete records before the damage; headers are compared key
// by key.
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "batch/checkpoint.h"
#include "check.h"
#include "common/digest.h"
#include "rt/error.h"

using namespace rt;
using rt_test::error_of;

namespace {

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (std::bit_cast<std::uint64_t>(a[i]) != std::bit_cast<std::uint64_t>(b[i])) return false;
    return true;
}

const CheckpointHeader kHeader{{"rt", "0.1.0"},
                               {"scene", "sha256 " + sha256_hex("102 0 0 5 ...")},
                               {"options", "-d 7 -w 0.01 -m trace -s 1"},
                               {"size", "4x3"}};

std::vector<CheckpointRow> some_rows() {
    std::vector<CheckpointRow> rows;
    for (std::uint32_t y = 0; y < 3; ++y) {
        CheckpointRow row;
        row.y = y;
        for (int i = 0; i < 12; ++i) row.values.push_back(0.1 * i + y);
        rows.push_back(row);
    }
    // Values whose bits matter: -0, a subnormal, infinity, a NaN with a payload.
    rows[1].values[0] = -0.0;
    rows[1].values[1] = std::numeric_limits<double>::denorm_min();
    rows[1].values[2] = std::numeric_limits<double>::infinity();
    rows[1].values[3] = std::bit_cast<double>(std::uint64_t{0x7ff8000000000123});
    rows[2].pass = 0;
    rows[2].x0 = 1;
    rows[2].values.resize(9);
    return rows;
}

std::string file_of(const std::vector<CheckpointRow>& rows) {
    std::string bytes = encode_checkpoint_start(kHeader);
    for (const CheckpointRow& row : rows) bytes += encode_checkpoint_row(row);
    return bytes;
}

}  // namespace

TEST(sha256_matches_the_standards_examples) {
    CHECK_EQ(sha256_hex(""),
             std::string("e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"));
    CHECK_EQ(sha256_hex("abc"),
             std::string("ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"));
    CHECK_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
             std::string("248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1"));
    // A million 'a', given in uneven pieces: the split must not matter.
    Sha256 hash;
    const std::string piece(997, 'a');
    std::size_t given = 0;
    while (given + piece.size() <= 1000000) {
        hash.update(piece);
        given += piece.size();
    }
    hash.update(std::string(1000000 - given, 'a'));
    CHECK_EQ(to_hex(hash.finish()),
             std::string("cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0"));
    // Lengths around the padding's edges (55, 56, 63, 64 bytes) agree with one-piece hashing.
    for (std::size_t n : {55u, 56u, 63u, 64u, 65u, 119u, 120u}) {
        const std::string text(n, 'x');
        Sha256 split;
        split.update(text.substr(0, n / 3));
        split.update(text.substr(n / 3));
        CHECK_EQ(to_hex(split.finish()), sha256_hex(text));
    }
}

TEST(rows_come_back_bit_for_bit) {
    const auto rows = some_rows();
    const CheckpointContents c = read_checkpoint(file_of(rows));
    CHECK(c.header == kHeader);
    CHECK_EQ(c.rows.size(), rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
        CHECK_EQ(int(c.rows[i].pass), int(rows[i].pass));
        CHECK_EQ(c.rows[i].y, rows[i].y);
        CHECK_EQ(c.rows[i].x0, rows[i].x0);
        CHECK(same_bits(c.rows[i].values, rows[i].values));
    }
    CHECK(!c.damaged);
    CHECK_EQ(c.kept_bytes, file_of(rows).size());
}

// Cut after every byte: once the header is whole, the complete rows before the cut are kept
// and nothing else; before that, the file is refused.
TEST(a_file_cut_anywhere_keeps_its_complete_records) {
    const auto rows = some_rows();
    const std::string whole = file_of(rows);
    std::vector<std::size_t> ends{encode_checkpoint_start(kHeader).size()};
    for (const CheckpointRow& row : rows)
        ends.push_back(ends.back() + encode_checkpoint_row(row).size());
    for (std::size_t cut = 0; cut <= whole.size(); ++cut) {
        const std::string_view part(whole.data(), cut);
        if (cut < ends[0]) {
            CHECK(!error_of([&] { read_checkpoint(part); }).empty());
            continue;
        }
        const CheckpointContents c = read_checkpoint(part);
        std::size_t complete = 0;
        while (complete + 1 < ends.size() && ends[complete + 1] <= cut) ++complete;
        CHECK_EQ(c.rows.size(), complete);
        CHECK_EQ(c.kept_bytes, ends[complete]);
        CHECK_EQ(c.damaged, cut != ends[complete]);
    }
}

// A byte changed anywhere in a row record: the rows before it are kept, it and everything
// after are the damaged tail.
TEST(a_damaged_record_ends_what_is_kept) {
    const auto rows = some_rows();
    const std::string whole = file_of(rows);
    const std::size_t start = encode_checkpoint_start(kHeader).size();
    const std::size_t first = encode_checkpoint_row(rows[0]).size();
    const std::size_t second = encode_checkpoint_row(rows[1]).size();
    for (std::size_t at = start + first; at < start + first + second; ++at) {
        std::string damaged = whole;
        damaged[at] = static_cast<char>(damaged[at] ^ 0x20);
        const CheckpointContents c = read_checkpoint(damaged);
        CHECK_EQ(c.rows.size(), 1u);
        CHECK(c.damaged);
        CHECK_EQ(c.kept_bytes, start + first);
    }
    // The header damaged: nothing can be trusted.
    std::string bad_header = whole;
    bad_header[kCheckpointMagic.size() + 12] ^= 1;
    CHECK_CONTAINS(error_of([&] { read_checkpoint(bad_header); }),
                   "header is incomplete or damaged");
    CHECK_CONTAINS(error_of([&] { read_checkpoint("P6\n1 1\n255\n..."); }), "not an rt checkpoint");
}

TEST(headers_are_compared_key_by_key) {
    CHECK_EQ(checkpoint_differences(kHeader, kHeader), std::string());
    CheckpointHeader other = kHeader;
    other[2].second = "-d 5 -w 0.01 -m trace -s 1";
    other.emplace_back("region", "0,4,0,2");
    other.erase(other.begin() + 3);
    CHECK_EQ(checkpoint_differences(kHeader, other),
             std::string("options: -d 7 -w 0.01 -m trace -s 1 here, -d 5 -w 0.01 -m trace -s 1 in "
                         "the checkpoint; size: 4x3 here, none in the checkpoint; region: none "
                         "here, 0,4,0,2 in the checkpoint"));
}
