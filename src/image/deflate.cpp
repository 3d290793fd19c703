// The deflate encoder: LZ77 with hash chains and lazy matching as zlib does it at level 6,
// then per block the cheapest of dynamic Huffman codes, the fixed codes and stored bytes.
#include "image/deflate.h"

#include <algorithm>
#include <array>
#include <bit>
#include <vector>

#include "deflate_tables.h"

namespace rt {

namespace {

using namespace deflate_format;

// zlib's level-6 search: chains of at most 128 candidates (a quarter of that once a match of
// 8 is in hand), no lazy search past a match of 16, and stop at a match of 128.
constexpr int kMaxChain = 128;
constexpr int kGoodLength = 8;
constexpr int kMaxLazy = 16;
constexpr int kNiceLength = 128;
// A match of 3 this far back costs more bits than its three literals.
constexpr std::size_t kTooFar = 4096;
// zlib keeps a match's whole length inside the window it can see; so do we.
constexpr std::size_t kMaxDistance = kWindowSize - kMaxMatch - kMinMatch - 1;
// Hash bits: 15 (zlib's at its default memory level), fewer for an input too short to fill
// them, so that a short text chunk or checkpoint record does not fill half a megabyte of
// tables. The same function of the input on every machine.
constexpr int kMaxHashBits = 15;
constexpr int kMinHashBits = 8;
int hash_bits_for(std::size_t size) {
    return std::clamp(static_cast<int>(std::bit_width(size)), kMinHashBits, kMaxHashBits);
}
// Positions back to the window's start: the window, or the input if it is shorter (every
// position of a short input is its own slot, as it would be in the whole window).
std::size_t chain_slots_for(std::size_t size) {
    return std::min<std::size_t>(kWindowSize, std::bit_ceil(std::max<std::size_t>(size, 1)));
}
// Symbols per block: zlib's at its default memory level. Each block gets its own codes.
constexpr std::size_t kBlockSymbols = 16384;

// A literal (distance 0, value the byte) or a match (value its length).
struct Symbol {
    std::uint16_t value;
    std::uint16_t distance;
};

int length_code(int length) {  // 257-285
    static const std::array<std::uint8_t, kMaxMatch + 1> table = [] {
        std::array<std::uint8_t, kMaxMatch + 1> t{};
        for (int code = 0; code < 29; ++code) {
            const int end = code == 28 ? kMaxMatch + 1 : kLengthBase[code + 1];
            for (int l = kLengthBase[code]; l < end; ++l) t[l] = static_cast<std::uint8_t>(code);
        }
        return t;
    }();
    return 257 + table[length];
}

int distance_code(int distance) {  // 0-29
    // Distances up to 256 by table; above that the code depends only on (distance - 1) >> 7.
    static const std::array<std::uint8_t, 512> table = [] {
        std::array<std::uint8_t, 512> t{};
        for (int code = 0; code < kDistanceCodes; ++code) {
            const int end = code == kDistanceCodes - 1 ? kWindowSize + 1 : kDistanceBase[code + 1];
            for (int d = kDistanceBase[code]; d < end; ++d) {
                const int slot = d <= 256 ? d - 1 : 256 + ((d - 1) >> 7);
                t[slot] = static_cast<std::uint8_t>(code);
            }
        }
        return t;
    }();
    return table[distance <= 256 ? distance - 1 : 256 + ((distance - 1) >> 7)];
}

// Bits are packed from the least significant end, as deflate wants them.
class BitWriter {
  public:
    explicit BitWriter(std::string& out) : out_(out) {}
    void put(std::uint32_t value, int count) {
        bits_ |= static_cast<std::uint64_t>(value) << count_;
        count_ += count;
        while (count_ >= 8) {
            out_.push_back(static_cast<char>(bits_ & 0xFF));
            bits_ >>= 8;
            count_ -= 8;
        }
    }
    void align() {
        if (count_ > 0) put(0, 8 - count_);
    }

  private:
    std::string& out_;
    std::uint64_t bits_ = 0;
    int count_ = 0;
};

}  // namespace

std::vector<std::uint8_t> huffman_code_lengths(const std::vector<std::uint32_t>& freq, int limit) {
    std::vector<std::uint8_t> lengths(freq.size(), 0);
    struct Item {
        std::uint64_t weight;
        int left;   // -1 for a leaf
        int right;  // a leaf's symbol, else the second item
    };
    std::vector<Item> pool;
    std::vector<int> leaves;
    for (std::size_t s = 0; s < freq.size(); ++s) {
        if (freq[s] == 0) continue;
        pool.push_back({freq[s], -1, static_cast<int>(s)});
        leaves.push_back(static_cast<int>(pool.size()) - 1);
    }
    if (leaves.empty()) return lengths;
    if (leaves.size() == 1) {
        lengths[pool[leaves[0]].right] = 1;
        return lengths;
    }
    std::stable_sort(leaves.begin(), leaves.end(),
                     [&](int a, int b) { return pool[a].weight < pool[b].weight; });
    // Each level packages the previous list's items in pairs and merges the packages with
    // the leaves; a leaf's length is how often it occurs in the final list's first 2n - 2.
    std::vector<int> list = leaves;
    std::vector<int> merged;
    for (int level = 1; level < limit; ++level) {
        merged.clear();
        std::size_t leaf = 0;
        std::size_t pair = 0;
        while (leaf < leaves.size() || pair + 1 < list.size()) {
            const bool take_leaf =
                pair + 1 >= list.size() ||
                (leaf < leaves.size() && pool[leaves[leaf]].weight <=
                                             pool[list[pair]].weight + pool[list[pair + 1]].weight);
            if (take_leaf) {
                merged.push_back(leaves[leaf++]);
            } else {
                pool.push_back({pool[list[pair]].weight + pool[list[pair + 1]].weight, list[pair],
                                list[pair + 1]});
                merged.push_back(static_cast<int>(pool.size()) - 1);
                pair += 2;
            }
        }
        list.swap(merged);
    }
    std::vector<int> stack;
    for (std::size_t i = 0; i < 2 * leaves.size() - 2; ++i) {
        stack.push_back(list[i]);
        while (!stack.empty()) {
            const Item item = pool[stack.back()];
            stack.pop_back();
            if (item.left < 0) {
                ++lengths[item.right];
            } else {
                stack.push_back(item.left);
                stack.push_back(item.right);
            }
        }
    }
    return lengths;
}

namespace {

// Canonical codes for the lengths (RFC 1951, 3.2.2), bit-reversed for the writer.
std::vector<std::uint16_t> canonical_codes(const std::vector<std::uint8_t>& lengths) {
    std::array<int, kMaxCodeBits + 1> count{};
    for (const std::uint8_t l : lengths) ++count[l];
    count[0] = 0;
    std::array<int, kMaxCodeBits + 2> next{};
    for (int bits = 1; bits <= kMaxCodeBits; ++bits)
        next[bits + 1] = (next[bits] + count[bits]) << 1;
    std::vector<std::uint16_t> codes(lengths.size(), 0);
    for (std::size_t s = 0; s < lengths.size(); ++s) {
        const int l = lengths[s];
        if (l == 0) continue;
        const int code = next[l]++;
        codes[s] = static_cast<std::uint16_t>(reverse_bits(code, l));
    }
    return codes;
}

// deflate wants at least one distance code, and zlib's decoder refuses an incomplete code
// unless it has a single symbol; two symbols in use always give a complete code.
void use_at_least_two(std::vector<std::uint32_t>& freq) {
    int used = 0;
    for (const std::uint32_t f : freq) used += f != 0;
    for (std::size_t s = 0; used < 2 && s < freq.size(); ++s)
        if (freq[s] == 0) {
            freq[s] = 1;
            ++used;
        }
}

// A code and how it is written.
struct Code {
    std::vector<std::uint8_t> lengths;
    std::vector<std::uint16_t> codes;
};

Code make_code(std::vector<std::uint8_t> lengths) {
    Code c;
    c.codes = canonical_codes(lengths);
    c.lengths = std::move(lengths);
    return c;
}

const Code& fixed_literal_length_code() {
    static const Code code = [] {
        std::vector<std::uint8_t> lengths(288);
        for (int s = 0; s < 288; ++s)
            lengths[s] = static_cast<std::uint8_t>(fixed_literal_length_bits(s));
        return make_code(std::move(lengths));
    }();
    return code;
}

const Code& fixed_distance_code() {
    static const Code code = make_code(std::vector<std::uint8_t>(32, kFixedDistanceBits));
    return code;
}

// One entry of the run-length coded code lengths: a symbol 0-18 and its extra bits.
struct LengthSymbol {
    std::uint8_t symbol;
    std::uint8_t extra;
};

// The code lengths as symbols 0-15, 16 (repeat the previous 3-6 times), 17 (3-10 zeros) and
// 18 (11-138 zeros).
std::vector<LengthSymbol> run_length_code(const std::vector<std::uint8_t>& lengths) {
    std::vector<LengthSymbol> out;
    for (std::size_t i = 0; i < lengths.size();) {
        const std::uint8_t l = lengths[i];
        std::size_t run = 1;
        while (i + run < lengths.size() && lengths[i + run] == l) ++run;
        i += run;
        if (l == 0) {
            while (run >= 11) {
                const std::size_t n = std::min<std::size_t>(run, 138);
                out.push_back({18, static_cast<std::uint8_t>(n - 11)});
                run -= n;
            }
            if (run >= 3) {
                out.push_back({17, static_cast<std::uint8_t>(run - 3)});
                run = 0;
            }
        } else {
            out.push_back({l, 0});
            --run;
            while (run >= 3) {
                const std::size_t n = std::min<std::size_t>(run, 6);
                out.push_back({16, static_cast<std::uint8_t>(n - 3)});
                run -= n;
            }
        }
        for (; run > 0; --run) out.push_back({l, 0});
    }
    return out;
}

int length_symbol_extra_bits(int symbol) {
    return symbol == 16 ? 2 : symbol == 17 ? 3 : symbol == 18 ? 7 : 0;
}

class Encoder {
  public:
    Encoder(std::string_view data, std::string& out)
        : data_(reinterpret_cast<const unsigned char*>(data.data())),
          size_(data.size()),
          writer_(out),
          hash_bits_(hash_bits_for(size_)),
          slot_mask_(chain_slots_for(size_) - 1),
          head_(std::size_t{1} << hash_bits_, -1),
          prev_(slot_mask_ + 1, -1) {
        symbols_.reserve(kBlockSymbols);
    }

    void run();

  private:
    std::size_t hash(std::size_t p) const {
        const std::uint32_t v =
            (std::uint32_t{data_[p]} << 16) | (std::uint32_t{data_[p + 1]} << 8) | data_[p + 2];
        return (v * 2654435761u) >> (32 - hash_bits_);
    }
    // Enters position p (which has three bytes after it) and returns the previous position
    // with the same hash, or -1.
    std::int64_t insert(std::size_t p) {
        const std::size_t h = hash(p);
        const std::int64_t previous = head_[h];
        prev_[p & slot_mask_] = previous;
        head_[h] = static_cast<std::int64_t>(p);
        return previous;
    }
    int longest_match(std::size_t pos, std::int64_t candidate, int best, std::size_t& start) const;
    void literal(unsigned char byte) {
        symbols_.push_back({byte, 0});
        ++block_bytes_;
    }
    void match(std::size_t distance, int length) {
        symbols_.push_back(
            {static_cast<std::uint16_t>(length), static_cast<std::uint16_t>(distance)});
        block_bytes_ += static_cast<std::size_t>(length);
    }
    void flush_block(bool last);
    void write_symbols(const Code& literal_length, const Code& distance);

    const unsigned char* data_;
    std::size_t size_;
    BitWriter writer_;
    int hash_bits_;
    std::size_t slot_mask_;
    std::vector<std::int64_t> head_;
    std::vector<std::int64_t> prev_;
    std::vector<Symbol> symbols_;
    std::size_t block_start_ = 0;  // the first input byte of the block being collected
    std::size_t block_bytes_ = 0;  // how many input bytes its symbols stand for
};

int Encoder::longest_match(std::size_t pos, std::int64_t candidate, int best,
                           std::size_t& start) const {
    const int max_length = static_cast<int>(std::min<std::size_t>(kMaxMatch, size_ - pos));
    if (best >= max_length) return best;
    const int nice = std::min(kNiceLength, max_length);
    int chain = best >= kGoodLength ? kMaxChain / 4 : kMaxChain;
    const std::int64_t limit =
        pos > kMaxDistance ? static_cast<std::int64_t>(pos - kMaxDistance) : 0;
    const unsigned char* here = data_ + pos;
    while (candidate >= limit && chain-- > 0) {
        const unsigned char* there = data_ + candidate;
        // Only a candidate that agrees at the current best length can beat it.
        if (there[best] == here[best] && there[0] == here[0] && there[1] == here[1]) {
            int length = 2;
            while (length < max_length && there[length] == here[length]) ++length;
            if (length > best) {
                best = length;
                start = static_cast<std::size_t>(candidate);
                if (length >= nice) break;
            }
        }
        candidate = prev_[static_cast<std::size_t>(candidate) & slot_mask_];
    }
    return best;
}

void Encoder::run() {
    // zlib's lazy evaluation: a match found at one position is emitted only if the next
    // position does not start a longer one.
    std::size_t pos = 0;
    bool literal_pending = false;
    int match_length = kMinMatch - 1;
    std::size_t match_start = 0;
    while (pos < size_) {
        std::int64_t candidate = -1;
        if (pos + kMinMatch <= size_) candidate = insert(pos);
        const int prev_length = match_length;
        const std::size_t prev_start = match_start;
        match_length = kMinMatch - 1;
        if (candidate >= 0 && prev_length < kMaxLazy &&
            pos - static_cast<std::size_t>(candidate) <= kMaxDistance) {
            match_length = longest_match(pos, candidate, prev_length, match_start);
            if (match_length == kMinMatch && pos - match_start > kTooFar)
                match_length = kMinMatch - 1;
        }
        if (prev_length >= kMinMatch && match_length <= prev_length) {
            // The match that started at pos - 1 wins; its bytes from pos + 1 on enter the
            // hash chains (pos already has).
            const std::size_t end = pos - 1 + static_cast<std::size_t>(prev_length);
            match(pos - 1 - prev_start, prev_length);
            for (std::size_t p = pos + 1; p < end; ++p)
                if (p + kMinMatch <= size_) insert(p);
            pos = end;
            literal_pending = false;
            match_length = kMinMatch - 1;
        } else {
            if (literal_pending) literal(data_[pos - 1]);
            literal_pending = true;
            ++pos;
        }
        if (symbols_.size() >= kBlockSymbols) flush_block(false);
    }
    if (literal_pending) literal(data_[size_ - 1]);
    flush_block(true);
}

void Encoder::write_symbols(const Code& literal_length, const Code& distance) {
    for (const Symbol& s : symbols_) {
        if (s.distance == 0) {
            writer_.put(literal_length.codes[s.value], literal_length.lengths[s.value]);
            continue;
        }
        const int lc = length_code(s.value);
        writer_.put(literal_length.codes[lc], literal_length.lengths[lc]);
        writer_.put(s.value - kLengthBase[lc - 257], kLengthExtra[lc - 257]);
        const int dc = distance_code(s.distance);
        writer_.put(distance.codes[dc], distance.lengths[dc]);
        writer_.put(s.distance - kDistanceBase[dc], kDistanceExtra[dc]);
    }
    writer_.put(literal_length.codes[kEndOfBlock], literal_length.lengths[kEndOfBlock]);
}

void Encoder::flush_block(bool last) {
    std::vector<std::uint32_t> literal_freq(kLiteralLengthCodes, 0);
    std::vector<std::uint32_t> distance_freq(kDistanceCodes, 0);
    // The bits the symbols' extra bits take: the same under every code.
    std::uint64_t extra_bits = 0;
    for (const Symbol& s : symbols_) {
        if (s.distance == 0) {
            ++literal_freq[s.value];
            continue;
        }
        const int lc = length_code(s.value);
        const int dc = distance_code(s.distance);
        ++literal_freq[lc];
        ++distance_freq[dc];
        extra_bits += kLengthExtra[lc - 257] + kDistanceExtra[dc];
    }
    literal_freq[kEndOfBlock] = 1;
    auto cost = [&](const std::vector<std::uint8_t>& literal_lengths,
                    const std::vector<std::uint8_t>& distance_lengths) {
        std::uint64_t bits = extra_bits;
        for (int s = 0; s < kLiteralLengthCodes; ++s)
            bits += std::uint64_t{literal_freq[s]} * literal_lengths[s];
        for (int s = 0; s < kDistanceCodes; ++s)
            bits += std::uint64_t{distance_freq[s]} * distance_lengths[s];
        return bits;
    };

    // Dynamic codes, and the code-length code that describes them.
    use_at_least_two(distance_freq);
    Code literal_tree = make_code(huffman_code_lengths(literal_freq, kMaxCodeBits));
    Code distance_tree = make_code(huffman_code_lengths(distance_freq, kMaxCodeBits));
    int hlit = kLiteralLengthCodes;
    while (hlit > 257 && literal_tree.lengths[hlit - 1] == 0) --hlit;
    int hdist = kDistanceCodes;
    while (hdist > 1 && distance_tree.lengths[hdist - 1] == 0) --hdist;
    std::vector<std::uint8_t> all_lengths(literal_tree.lengths.begin(),
                                          literal_tree.lengths.begin() + hlit);
    all_lengths.insert(all_lengths.end(), distance_tree.lengths.begin(),
                       distance_tree.lengths.begin() + hdist);
    const std::vector<LengthSymbol> runs = run_length_code(all_lengths);
    std::vector<std::uint32_t> length_freq(kCodeLengthCodes, 0);
    for (const LengthSymbol& r : runs) ++length_freq[r.symbol];
    use_at_least_two(length_freq);
    const Code length_tree = make_code(huffman_code_lengths(length_freq, kMaxCodeLengthBits));
    int hclen = kCodeLengthCodes;
    while (hclen > 4 && length_tree.lengths[kCodeLengthOrder[hclen - 1]] == 0) --hclen;
    std::uint64_t dynamic_bits = 3 + 5 + 5 + 4 + 3 * static_cast<std::uint64_t>(hclen) +
                                 cost(literal_tree.lengths, distance_tree.lengths);
    for (const LengthSymbol& r : runs)
        dynamic_bits += length_tree.lengths[r.symbol] + length_symbol_extra_bits(r.symbol);

    std::vector<std::uint8_t> fixed_distance_lengths(kDistanceCodes, kFixedDistanceBits);
    std::vector<std::uint8_t> fixed_literal_lengths(
        fixed_literal_length_code().lengths.begin(),
        fixed_literal_length_code().lengths.begin() + kLiteralLengthCodes);
    const std::uint64_t fixed_bits = 3 + cost(fixed_literal_lengths, fixed_distance_lengths);

    // Stored: a 65535-byte piece at most per stored block, each with a header, padding and
    // its length twice.
    const std::size_t pieces = std::max<std::size_t>(1, (block_bytes_ + 65534) / 65535);
    const std::uint64_t stored_bits = pieces * (3 + 7 + 32) + 8 * std::uint64_t{block_bytes_};

    if (stored_bits < dynamic_bits && stored_bits < fixed_bits) {
        std::size_t at = block_start_;
        const std::size_t end = block_start_ + block_bytes_;
        do {
            const std::size_t n = std::min<std::size_t>(65535, end - at);
            writer_.put(last && at + n == end ? 1 : 0, 1);
            writer_.put(0, 2);
            writer_.align();
            writer_.put(static_cast<std::uint32_t>(n), 16);
            writer_.put(static_cast<std::uint32_t>(~n & 0xFFFF), 16);
            for (std::size_t i = 0; i < n; ++i) writer_.put(data_[at + i], 8);
            at += n;
        } while (at < end);
    } else if (fixed_bits <= dynamic_bits) {
        writer_.put(last ? 1 : 0, 1);
        writer_.put(1, 2);
        write_symbols(fixed_literal_length_code(), fixed_distance_code());
    } else {
        writer_.put(last ? 1 : 0, 1);
        writer_.put(2, 2);
        writer_.put(static_cast<std::uint32_t>(hlit - 257), 5);
        writer_.put(static_cast<std::uint32_t>(hdist - 1), 5);
        writer_.put(static_cast<std::uint32_t>(hclen - 4), 4);
        for (int i = 0; i < hclen; ++i) writer_.put(length_tree.lengths[kCodeLengthOrder[i]], 3);
        for (const LengthSymbol& r : runs) {
            writer_.put(length_tree.codes[r.symbol], length_tree.lengths[r.symbol]);
            writer_.put(r.extra, length_symbol_extra_bits(r.symbol));
        }
        write_symbols(literal_tree, distance_tree);
    }
    if (last) writer_.align();
    symbols_.clear();
    block_start_ += block_bytes_;
    block_bytes_ = 0;
}

}  // namespace

std::string deflate(std::string_view data) {
    std::string out;
    out.reserve(data.size() / 2 + 64);
    Encoder(data, out).run();
    return out;
}

std::string zlib_compress(std::string_view data) {
    // CMF 0x78: deflate with a 32 KiB window; FLG 0x9C: the default level, and a check value
    // that makes CMF * 256 + FLG a multiple of 31.
    std::string out = "\x78\x9C";
    out += deflate(data);
    const std::uint32_t check = adler32(data);
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>(check >> shift));
    return out;
}

}  // namespace rt
