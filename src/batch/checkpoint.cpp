#include "batch/checkpoint.h"

#include <bit>
#include <cstring>
#include <map>

#include "image/deflate.h"  // crc32
#include "rt/error.h"

namespace rt {

namespace {

constexpr std::string_view kRecordMagic = "RTCK";
constexpr char kHeaderType = 'H';
constexpr char kRowType = 'R';
// A row of at most 16384 pixels (rt's widest image), three values each.
constexpr std::uint32_t kMaxRowValues = 3 * 16384;

void put_u32(std::string& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}

std::uint32_t get_u32(std::string_view bytes, std::size_t at) {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i)
        v |= std::uint32_t{static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(i)])}
             << (8 * i);
    return v;
}

std::string record(char type, std::string_view payload) {
    std::string framed(kRecordMagic);
    std::string checked(1, type);
    put_u32(checked, static_cast<std::uint32_t>(payload.size()));
    checked += payload;
    framed += checked;
    put_u32(framed, crc32(checked));
    return framed;
}

// The record at `at`, when complete and its checksum holds: its type and payload, and where
// the next one starts.
struct Record {
    char type = 0;
    std::string_view payload;
    std::size_t end = 0;
};

bool record_at(std::string_view bytes, std::size_t at, std::uint32_t max_payload, Record& out) {
    if (bytes.size() - at < kRecordMagic.size() + 5 + 4) return false;
    if (bytes.substr(at, kRecordMagic.size()) != kRecordMagic) return false;
    const std::size_t checked = at + kRecordMagic.size();
    const std::uint32_t length = get_u32(bytes, checked + 1);
    if (length > max_payload || bytes.size() - checked - 5 - 4 < length) return false;
    if (get_u32(bytes, checked + 5 + length) != crc32(bytes.substr(checked, 5 + length)))
        return false;
    out = {bytes[checked], bytes.substr(checked + 5, length), checked + 5 + length + 4};
    return true;
}

CheckpointHeader parse_header(std::string_view text) {
    CheckpointHeader header;
    while (!text.empty()) {
        const std::size_t end = text.find('\n');
        const std::string_view line = text.substr(0, end);
        const std::size_t colon = line.find(": ");
        if (colon == std::string_view::npos || end == std::string_view::npos)
            throw CheckpointHeaderDamaged("its header is not rt's (a line without 'key: value')");
        header.emplace_back(std::string(line.substr(0, colon)),
                            std::string(line.substr(colon + 2)));
        text.remove_prefix(end + 1);
    }
    return header;
}

bool parse_row(std::string_view payload, CheckpointRow& row) {
    if (payload.size() < 13) return false;
    row.pass = static_cast<std::uint8_t>(payload[0]);
    row.y = get_u32(payload, 1);
    row.x0 = get_u32(payload, 5);
    const std::uint32_t count = get_u32(payload, 9);
    if (row.pass > 1 || count > kMaxRowValues || count % 3 != 0 ||
        payload.size() != 13 + 8 * std::size_t{count})
        return false;
    row.values.resize(count);
    for (std::uint32_t i = 0; i < count; ++i) {
        std::uint64_t bits = 0;
        for (int k = 0; k < 8; ++k)
            bits |= std::uint64_t{static_cast<unsigned char>(
                        payload[13 + 8 * i + static_cast<std::size_t>(k)])}
                    << (8 * k);
        row.values[i] = std::bit_cast<double>(bits);
    }
    return true;
}

}  // namespace

std::string encode_checkpoint_start(const CheckpointHeader& header) {
    std::string text;
    for (const auto& [key, value] : header) text += key + ": " + value + "\n";
    return std::string(kCheckpointMagic) + record(kHeaderType, text);
}

std::string encode_checkpoint_row(const CheckpointRow& row) {
    std::string payload(1, static_cast<char>(row.pass));
    put_u32(payload, row.y);
    put_u32(payload, row.x0);
    put_u32(payload, static_cast<std::uint32_t>(row.values.size()));
    for (const double v : row.values) {
        const auto bits = std::bit_cast<std::uint64_t>(v);
        for (int k = 0; k < 8; ++k) payload += static_cast<char>((bits >> (8 * k)) & 0xff);
    }
    return record(kRowType, payload);
}

CheckpointContents read_checkpoint(std::string_view bytes) {
    if (bytes.substr(0, kCheckpointMagic.size()) != kCheckpointMagic)
        throw Error("it is not an rt checkpoint (it does not start with 'rt checkpoint 1')");
    Record header;
    if (!record_at(bytes, kCheckpointMagic.size(), kMaxCheckpointHeader, header) ||
        header.type != kHeaderType)
        throw CheckpointHeaderDamaged("its header is incomplete or damaged");
    CheckpointContents contents;
    contents.header = parse_header(header.payload);
    std::size_t at = header.end;
    Record next;
    CheckpointRow row;
    while (record_at(bytes, at, 13 + 8 * kMaxRowValues, next) && next.type == kRowType &&
           parse_row(next.payload, row)) {
        contents.rows.push_back(std::move(row));
        row = {};
        at = next.end;
    }
    contents.kept_bytes = at;
    contents.damaged = at != bytes.size();
    return contents;
}

std::string checkpoint_differences(const CheckpointHeader& wanted, const CheckpointHeader& found) {
    std::map<std::string, std::string> in_file(found.begin(), found.end());
    std::string differences;
    const auto add = [&](const std::string& clause) {
        if (!differences.empty()) differences += "; ";
        differences += clause;
    };
    for (const auto& [key, value] : wanted) {
        const auto it = in_file.find(key);
        if (it == in_file.end())
            add(key + ": " + value + " here, none in the checkpoint");
        else if (it->second != value)
            add(key + ": " + value + " here, " + it->second + " in the checkpoint");
        if (it != in_file.end()) in_file.erase(it);
    }
    for (const auto& [key, value] : in_file)
        add(key + ": none here, " + value + " in the checkpoint");
    return differences;
}

}  // namespace rt
