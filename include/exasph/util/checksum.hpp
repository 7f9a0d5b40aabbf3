#pragma once
#include <cstdint>
#include <cstring>
#include <string>

#include "exasph/util/annotate.hpp"

namespace exasph {

// 64-bit mixing function (the splitmix64 finaliser): every input bit affects every output bit.
EXASPH_HD inline std::uint64_t mix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// Bit pattern of a floating-point value (float or double), widened to 64 bits.
template <class T>
EXASPH_HD std::uint64_t float_bits(T v) {
    if constexpr (sizeof(T) == 8) {
        std::uint64_t b;
        std::memcpy(&b, &v, 8);
        return b;
    } else {
        std::uint32_t b;
        std::memcpy(&b, &v, 4);
        return b;
    }
}

// A particle's 64-bit hash folded to the 32 bits that the state guard keeps and the seals sum.
EXASPH_HD inline std::uint32_t fold_hash(std::uint64_t h) {
    return std::uint32_t(h ^ (h >> 32));
}

// Chains values into one hash: order matters within a chain.
class HashChain {
  public:
    explicit HashChain(std::uint64_t seed = 0) : h_(mix64(seed)) {}
    HashChain& add(std::uint64_t v) {
        h_ = mix64(h_ ^ v);
        return *this;
    }
    template <class T>
    HashChain& add_float(T v) {
        return add(float_bits(v));
    }
    std::uint64_t value() const { return h_; }

  private:
    std::uint64_t h_;
};

inline std::string hex64(std::uint64_t v) {
    static const char* digits = "0123456789abcdef";
    std::string s(16, '0');
    for (int i = 15; i >= 0; --i, v >>= 4) s[i] = digits[v & 15];
    return s;
}

} // namespace exasph
