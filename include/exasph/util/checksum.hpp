#pragma once
#include <cstdint>
#include <cstring>
#include <string>

namespace exasph {

// 64-bit mixing function (the splitmix64 finaliser): every input bit affects every output bit.
inline std::uint64_t mix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// Bit pattern of a floating-point value (float or double), widened to 64 bits.
template <class T>
std::uint64_t float_bits(T v) {
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
