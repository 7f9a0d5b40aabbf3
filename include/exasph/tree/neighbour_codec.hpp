#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <new>
#include <utility>
#include <vector>

#include <sys/mman.h>

#if defined(__AVX512F__) || defined(__AVX2__)
#include <immintrin.h>
#endif

// Building blocks of the compact neighbour lists (tree/neighbour_lists.hpp): variable-length
// integers, bit fields read from byte records, the expansion of a hit mask into particle indices,
// and a per-thread arena that holds the records. No SPH here.
namespace exasph::codec {

// Bytes that may be read past the end of a record (the 64-bit loads below): every record is
// followed by at least this many bytes of its block.
inline constexpr std::size_t kReadPad = 8;

// LEB128: seven bits per byte, low bits first; small values (the usual leaf sizes and gaps)
// take one byte.
inline void put_varint(std::vector<std::uint8_t>& out, std::uint32_t v) {
    while (v >= 0x80u) {
        out.push_back(std::uint8_t(v | 0x80u));
        v >>= 7;
    }
    out.push_back(std::uint8_t(v));
}

inline std::uint32_t get_varint(const std::uint8_t*& p) {
    std::uint32_t v = 0;
    for (int shift = 0;; shift += 7) {
        const std::uint8_t b = *p++;
        v |= std::uint32_t(b & 0x7Fu) << shift;
        if (!(b & 0x80u)) return v;
    }
}

inline std::uint64_t load_u64(const std::uint8_t* p) {
    std::uint64_t v;
    std::memcpy(&v, p, sizeof v);
    return v; // little-endian: bit k of the record is bit k of the word
}

// `n` (<= 32) bits of `base` starting at bit `pos` (bit k of byte b is bit 8b + k).
inline std::uint32_t load_bits(const std::uint8_t* base, std::uint64_t pos, unsigned n) {
    const std::uint64_t w = load_u64(base + (pos >> 3)) >> (pos & 7u);
    return std::uint32_t(w & ((std::uint64_t(1) << n) - 1u));
}

// `n` (<= 64) bits starting at a byte boundary.
inline std::uint64_t load_word(const std::uint8_t* base, unsigned n) {
    const std::uint64_t w = load_u64(base);
    return n >= 64 ? w : w & ((std::uint64_t(1) << n) - 1u);
}

#if defined(__AVX2__) && !defined(__AVX512F__)
// For every byte value, the positions of its set bits in ascending order (then zeros): the
// expansion's shuffle rows on AVX2 (2 KiB, stays in L1 during a pass).
inline constexpr auto kByteBits = [] {
    std::array<std::array<std::uint8_t, 8>, 256> t{};
    for (unsigned m = 0; m < 256; ++m) {
        unsigned c = 0;
        for (unsigned k = 0; k < 8; ++k)
            if (m >> k & 1u) t[m][c++] = std::uint8_t(k);
    }
    return t;
}();
#endif

// Writes first + k for every set bit k of `mask` (ascending) to `out`; returns how many. `out`
// must have room for 32 more indices than the count (the vector path stores whole registers).
inline std::uint32_t expand_mask(std::uint32_t mask, std::uint32_t first, std::uint32_t* out) {
#if defined(__AVX512F__)
    const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    const __m512i lo = _mm512_add_epi32(_mm512_set1_epi32(int(first)), lane);
    const auto m0 = __mmask16(mask & 0xFFFFu);
    _mm512_storeu_si512(out, _mm512_maskz_compress_epi32(m0, lo));
    const auto c0 = std::uint32_t(std::popcount(mask & 0xFFFFu));
    // the upper half whatever it holds: a branch on it mispredicted at leaves of 16-32 particles
    // (each SPH pass 2-3 % faster on Zen 5); out has room for 32 more indices than the count
    const __m512i hi = _mm512_add_epi32(lo, _mm512_set1_epi32(16));
    _mm512_storeu_si512(out + c0, _mm512_maskz_compress_epi32(__mmask16(mask >> 16), hi));
    return std::uint32_t(std::popcount(mask));
#elif defined(__AVX2__)
    // AVX2 has no compress: each byte of the mask picks a row of kByteBits (its set bits'
    // positions, packed at the front), widened to 32 bits, offset and stored whole.
    std::uint32_t c = 0;
    for (unsigned byte = 0; byte < 4 && mask != 0; ++byte, mask >>= 8) {
        const unsigned m = mask & 0xFFu;
        const __m128i row = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(kByteBits[m].data()));
        const __m256i idx =
            _mm256_add_epi32(_mm256_cvtepu8_epi32(row), _mm256_set1_epi32(int(first + 8 * byte)));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + c), idx);
        c += std::uint32_t(std::popcount(m));
    }
    return c;
#else
    std::uint32_t c = 0;
    while (mask) {
        out[c++] = first + std::uint32_t(std::countr_zero(mask));
        mask &= mask - 1u;
    }
    return c;
#endif
}

// expand_mask for a mask of at most 16 bits, without branches on its value. On AVX2 both bytes
// are expanded whatever they hold; with expand_mask's early exit on a zero byte the branch
// mispredicted on about every other leaf (the density pass spent 28 % of its time decoding on
// Zen 2).
inline std::uint32_t expand_mask16(std::uint32_t mask, std::uint32_t first, std::uint32_t* out) {
#if defined(__AVX2__) && !defined(__AVX512F__)
    const unsigned lo = mask & 0xFFu, hi = (mask >> 8) & 0xFFu;
    const __m128i row_lo = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(kByteBits[lo].data()));
    const __m128i row_hi = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(kByteBits[hi].data()));
    const __m256i base = _mm256_set1_epi32(int(first));
    const __m256i eight = _mm256_set1_epi32(8);
    const auto c_lo = std::uint32_t(std::popcount(lo));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out),
                        _mm256_add_epi32(_mm256_cvtepu8_epi32(row_lo), base));
    _mm256_storeu_si256(
        reinterpret_cast<__m256i*>(out + c_lo),
        _mm256_add_epi32(_mm256_cvtepu8_epi32(row_hi), _mm256_add_epi32(base, eight)));
    return c_lo + std::uint32_t(std::popcount(hi));
#else
    return expand_mask(mask, first, out);
#endif
}

// expand_mask16 for a mask of at most 32 bits, four bytes expanded whatever they hold: the
// decoder's unit (a leaf of up to 32 particles in one call; with 16 bits a call, the loop's exit
// branch mispredicted at leaves of 17-32: density 2 %, IAD 3 % faster on Zen 2).
inline std::uint32_t expand_mask32(std::uint32_t mask, std::uint32_t first, std::uint32_t* out) {
#if defined(__AVX2__) && !defined(__AVX512F__)
    const std::uint32_t c = expand_mask16(mask & 0xFFFFu, first, out);
    return c + expand_mask16(mask >> 16, first + 16, out + c);
#else
    return expand_mask(mask, first, out);
#endif
}

// Sets bit `pos` of a zero-initialised byte record.
inline void set_bit(std::uint8_t* base, std::uint64_t pos) {
    base[pos >> 3] |= std::uint8_t(1u << (pos & 7u));
}

// Appends bit fields of up to 32 bits to a byte record (bit k of the record is bit k % 8 of byte
// k / 8). The destination needs room for the whole record plus kReadPad bytes.
class BitWriter {
  public:
    explicit BitWriter(std::uint8_t* dst) : dst_(dst) {}
    // Without a branch on the fill (it mispredicted: a word completes every few fields of
    // irregular size): the low word is stored every time and kept once it is full.
    void put(std::uint32_t bits, unsigned n) {
        acc_ |= std::uint64_t(bits) << used_;
        used_ += n;
        const auto word = std::uint32_t(acc_);
        std::memcpy(dst_, &word, 4);
        const unsigned full = used_ >> 5; // 1 when a word is complete (used_ < 64)
        dst_ += 4 * full;
        acc_ >>= 32 * full;
        used_ -= 32 * full;
    }
    // Writes the pending bits and moves to the next byte boundary.
    void align() {
        std::memcpy(dst_, &acc_, 8); // within the padding
        dst_ += (used_ + 7) / 8;
        acc_ = 0;
        used_ = 0;
    }

  private:
    std::uint8_t* dst_;
    std::uint64_t acc_ = 0;
    unsigned used_ = 0;
};

// Records in large blocks: one arena per thread, so that storing needs no lock; reset() reuses
// the blocks for the next build, release() returns them to the operating system (the blocks are
// mapped pages, so the resident memory drops at once, unlike with a heap that keeps freed
// chunks). Records never move.
class Arena {
  public:
    const std::uint8_t* store(const std::vector<std::uint8_t>& rec) {
        const std::size_t need = rec.size() + kReadPad;
        while (cur_ < blocks_.size() && used_ + need > blocks_[cur_].size) {
            ++cur_;
            used_ = 0;
        }
        if (cur_ == blocks_.size()) {
            const std::size_t size = std::max(kBlockBytes, need);
            blocks_.emplace_back(size);
            used_ = 0;
        }
        std::uint8_t* dst = blocks_[cur_].data + used_;
        if (!rec.empty()) std::memcpy(dst, rec.data(), rec.size()); // (an empty one has no data)
        std::memset(dst + rec.size(), 0, kReadPad); // the padding that loads may read
        used_ += rec.size();
        return dst;
    }

    // Starts a new build; blocks that the previous build did not reach are freed.
    void reset() {
        if (cur_ + 1 < blocks_.size())
            blocks_.erase(blocks_.begin() + std::ptrdiff_t(cur_ + 1), blocks_.end());
        cur_ = 0;
        used_ = 0;
    }

    void release() {
        blocks_.clear();
        cur_ = 0;
        used_ = 0;
    }

    std::size_t bytes() const {
        std::size_t b = 0;
        for (const auto& bl : blocks_) b += bl.size;
        return b;
    }

  private:
    static constexpr std::size_t kBlockBytes = std::size_t(1) << 20;
    struct Block {
        std::uint8_t* data;
        std::size_t size;
        explicit Block(std::size_t n) : size(n) {
            void* p = mmap(nullptr, n, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
            if (p == MAP_FAILED) throw std::bad_alloc();
            data = static_cast<std::uint8_t*>(p);
        }
        Block(Block&& o) noexcept : data(std::exchange(o.data, nullptr)), size(o.size) {}
        Block& operator=(Block&& o) noexcept {
            std::swap(data, o.data);
            std::swap(size, o.size);
            return *this;
        }
        Block(const Block&) = delete;
        Block& operator=(const Block&) = delete;
        ~Block() {
            if (data) munmap(data, size);
        }
    };
    std::vector<Block> blocks_;
    std::size_t cur_ = 0, used_ = 0;
};

} // namespace exasph::codec
