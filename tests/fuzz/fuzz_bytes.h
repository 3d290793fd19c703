// The fuzzer's bytes read as a sequence of choices, for the structured cases (fuzz_cases.h)
// that build a valid file around fuzzed content: a mutation then changes what is built, not
// a checksum that makes every mutant fail at its first check. Past the end every read gives
// 0, which chooses the plain, valid option everywhere.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace rt_fuzz {

class FuzzBytes {
  public:
    explicit FuzzBytes(std::string_view bytes) : bytes_(bytes) {}

    std::uint8_t byte() {
        return at_ < bytes_.size() ? static_cast<std::uint8_t>(bytes_[at_++]) : 0;
    }
    // A number in [0, n), from as many bytes as n needs.
    std::uint32_t below(std::uint32_t n) {
        if (n <= 1) return 0;
        std::uint32_t v = byte();
        for (std::uint32_t range = 256; range < n && range <= 0xFFFFFF; range <<= 8)
            v = v << 8 | byte();
        return v % n;
    }
    std::uint32_t u32() {
        std::uint32_t v = 0;
        for (int i = 0; i < 4; ++i) v = v << 8 | byte();
        return v;
    }
    std::uint64_t u64() {
        const std::uint64_t high = u32();
        return high << 32 | u32();
    }
    // True about once in n reads (never once the bytes are used up): the deviations from a
    // valid file, so that most inputs stay valid.
    bool rare(std::uint32_t n) { return at_ < bytes_.size() && below(n) == n - 1; }
    // Up to n of the bytes, as they are.
    std::string_view take(std::size_t n) {
        const std::size_t k = n < bytes_.size() - at_ ? n : bytes_.size() - at_;
        const std::string_view out = bytes_.substr(at_, k);
        at_ += k;
        return out;
    }
    // Exactly n bytes: those left, then zeros.
    std::string exactly(std::size_t n) {
        std::string out(take(n));
        out.resize(n, '\0');
        return out;
    }
    // A word of 1 to max_length characters from `alphabet`.
    std::string word(std::string_view alphabet, std::uint32_t max_length) {
        std::string out(1 + below(max_length), ' ');
        for (char& c : out) c = alphabet[below(static_cast<std::uint32_t>(alphabet.size()))];
        return out;
    }

  private:
    std::string_view bytes_;
    std::size_t at_ = 0;
};

}  // namespace rt_fuzz
