// The deflate decoder, for reading PNG files back (and for testing the encoder).
#include <array>
#include <vector>

#include "deflate_tables.h"
#include "image/deflate.h"
#include "rt/error.h"

namespace rt {

namespace {

using namespace deflate_format;

// Bits from the least significant end of each byte, as deflate packs them. Reading past the
// end sees zeros until a code actually uses them, which is an error.
class BitReader {
  public:
    explicit BitReader(std::string_view data)
        : data_(reinterpret_cast<const unsigned char*>(data.data())), size_(data.size()) {}

    std::uint32_t peek(int n) {
        while (count_ < n && count_ <= 56) {
            if (pos_ < size_) bits_ |= static_cast<std::uint64_t>(data_[pos_]) << count_;
            ++pos_;  // may run past the end; skip() catches a read of those bits
            count_ += 8;
        }
        return static_cast<std::uint32_t>(bits_ & ((std::uint64_t{1} << n) - 1));
    }
    void skip(int n) {
        bits_ >>= n;
        count_ -= n;
        if (pos_ > size_ && pos_ * 8 - static_cast<std::size_t>(count_) > size_ * 8)
            throw Error("compressed data ends early");
    }
    std::uint32_t get(int n) {
        if (n == 0) return 0;
        const std::uint32_t v = peek(n);
        skip(n);
        return v;
    }
    void align() { skip(count_ % 8); }
    // Input bytes the bits taken so far came from.
    std::size_t consumed() const { return pos_ - static_cast<std::size_t>(count_) / 8; }

  private:
    const unsigned char* data_;
    std::size_t size_;
    std::size_t pos_ = 0;
    std::uint64_t bits_ = 0;
    int count_ = 0;
};

// A canonical Huffman code decoded by one lookup of its longest code's bits.
class HuffmanDecoder {
  public:
    void build(const std::uint8_t* lengths, int n) {
        std::array<int, kMaxCodeBits + 1> count{};
        for (int s = 0; s < n; ++s) ++count[lengths[s]];
        count[0] = 0;
        int left = 1;
        bits_ = 1;
        for (int l = 1; l <= kMaxCodeBits; ++l) {
            left = (left << 1) - count[l];
            if (left < 0) throw Error("compressed data has an over-subscribed code");
            if (count[l] != 0) bits_ = l;
        }
        // An incomplete code is accepted; its unused entries stay 0 and fail when read.
        table_.assign(std::size_t{1} << bits_, 0);
        std::array<int, kMaxCodeBits + 2> next{};
        for (int l = 1; l <= kMaxCodeBits; ++l) next[l + 1] = (next[l] + count[l]) << 1;
        for (int s = 0; s < n; ++s) {
            const int l = lengths[s];
            if (l == 0) continue;
            const int code = next[l]++;
            const int reversed = reverse_bits(code, l);
            for (std::size_t i = static_cast<std::size_t>(reversed); i < table_.size();
                 i += std::size_t{1} << l)
                table_[i] = static_cast<std::uint16_t>(s << 4 | l);
        }
    }
    int decode(BitReader& in) const {
        const std::uint16_t entry = table_[in.peek(bits_)];
        if (entry == 0) throw Error("compressed data has an invalid code");
        in.skip(entry & 15);
        return entry >> 4;
    }

  private:
    std::vector<std::uint16_t> table_;
    int bits_ = 1;
};

void read_dynamic_codes(BitReader& in, HuffmanDecoder& literal, HuffmanDecoder& distance) {
    const int hlit = static_cast<int>(in.get(5)) + 257;
    const int hdist = static_cast<int>(in.get(5)) + 1;
    const int hclen = static_cast<int>(in.get(4)) + 4;
    if (hlit > kLiteralLengthCodes || hdist > kDistanceCodes)
        throw Error("compressed data has too many codes");
    std::array<std::uint8_t, kCodeLengthCodes> length_lengths{};
    for (int i = 0; i < hclen; ++i)
        length_lengths[kCodeLengthOrder[i]] = static_cast<std::uint8_t>(in.get(3));
    HuffmanDecoder lengths_code;
    lengths_code.build(length_lengths.data(), kCodeLengthCodes);
    std::array<std::uint8_t, kLiteralLengthCodes + kDistanceCodes> lengths{};
    for (int i = 0; i < hlit + hdist;) {
        const int symbol = lengths_code.decode(in);
        if (symbol < 16) {
            lengths[i++] = static_cast<std::uint8_t>(symbol);
            continue;
        }
        std::uint8_t value = 0;
        int repeat = 0;
        if (symbol == 16) {
            if (i == 0) throw Error("compressed data repeats a code length that is not there");
            value = lengths[i - 1];
            repeat = 3 + static_cast<int>(in.get(2));
        } else if (symbol == 17) {
            repeat = 3 + static_cast<int>(in.get(3));
        } else {
            repeat = 11 + static_cast<int>(in.get(7));
        }
        if (i + repeat > hlit + hdist) throw Error("compressed data has too many code lengths");
        for (; repeat > 0; --repeat) lengths[i++] = value;
    }
    if (lengths[kEndOfBlock] == 0) throw Error("compressed data has no end-of-block code");
    literal.build(lengths.data(), hlit);
    distance.build(lengths.data() + hlit, hdist);
}

const std::pair<HuffmanDecoder, HuffmanDecoder>& fixed_codes() {
    static const auto codes = [] {
        std::array<std::uint8_t, 288> literal{};
        for (int s = 0; s < 288; ++s)
            literal[s] = static_cast<std::uint8_t>(fixed_literal_length_bits(s));
        const std::array<std::uint8_t, 32> distance = [] {
            std::array<std::uint8_t, 32> d{};
            d.fill(kFixedDistanceBits);
            return d;
        }();
        std::pair<HuffmanDecoder, HuffmanDecoder> c;
        c.first.build(literal.data(), 288);
        c.second.build(distance.data(), 32);
        return c;
    }();
    return codes;
}

void check_room(const std::string& out, std::size_t more, std::size_t max_size) {
    if (more > max_size - out.size())
        throw Error("compressed data is larger than expected (more than " +
                    std::to_string(max_size) + " bytes)");
}

}  // namespace

std::string inflate(std::string_view data, std::size_t max_size, std::size_t* consumed) {
    BitReader in(data);
    std::string out;
    HuffmanDecoder dynamic_literal;
    HuffmanDecoder dynamic_distance;
    bool last = false;
    while (!last) {
        last = in.get(1) != 0;
        const std::uint32_t type = in.get(2);
        if (type == 0) {
            in.align();
            const std::uint32_t length = in.get(16);
            if (in.get(16) != (~length & 0xFFFF))
                throw Error("compressed data has a damaged stored block");
            check_room(out, length, max_size);
            for (std::uint32_t i = 0; i < length; ++i) out.push_back(static_cast<char>(in.get(8)));
            continue;
        }
        if (type == 3) throw Error("compressed data has an invalid block type");
        if (type == 2) read_dynamic_codes(in, dynamic_literal, dynamic_distance);
        const HuffmanDecoder& literal = type == 1 ? fixed_codes().first : dynamic_literal;
        const HuffmanDecoder& distance = type == 1 ? fixed_codes().second : dynamic_distance;
        for (;;) {
            const int symbol = literal.decode(in);
            if (symbol < 256) {
                check_room(out, 1, max_size);
                out.push_back(static_cast<char>(symbol));
                continue;
            }
            if (symbol == kEndOfBlock) break;
            const int lc = symbol - 257;
            if (lc >= 29) throw Error("compressed data has an invalid length code");
            const std::size_t length = kLengthBase[lc] + in.get(kLengthExtra[lc]);
            const int dc = distance.decode(in);
            if (dc >= kDistanceCodes) throw Error("compressed data has an invalid distance code");
            const std::size_t back = kDistanceBase[dc] + in.get(kDistanceExtra[dc]);
            if (back > out.size()) throw Error("compressed data refers before its start");
            check_room(out, length, max_size);
            // Byte by byte: a match may overlap the bytes it produces.
            for (std::size_t from = out.size() - back, i = 0; i < length; ++i)
                out.push_back(out[from + i]);
        }
    }
    if (consumed) *consumed = in.consumed();
    return out;
}

std::string zlib_decompress(std::string_view data, std::size_t max_size) {
    if (data.size() < 6) throw Error("zlib stream is too short");
    const unsigned cmf = static_cast<unsigned char>(data[0]);
    const unsigned flg = static_cast<unsigned char>(data[1]);
    if ((cmf & 15) != 8 || (cmf >> 4) > 7 || (cmf * 256 + flg) % 31 != 0)
        throw Error("not a zlib deflate stream");
    if (flg & 0x20) throw Error("zlib stream needs a preset dictionary");
    std::size_t used = 0;
    std::string out = inflate(data.substr(2), max_size, &used);
    if (2 + used + 4 > data.size()) throw Error("zlib stream lacks its checksum");
    std::uint32_t check = 0;
    for (std::size_t i = 0; i < 4; ++i)
        check = check << 8 | static_cast<unsigned char>(data[2 + used + i]);
    if (check != adler32(out)) throw Error("zlib stream has a wrong checksum");
    return out;
}

}  // namespace rt
