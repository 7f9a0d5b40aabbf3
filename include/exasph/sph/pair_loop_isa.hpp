#pragma once
// The instruction set the CPU pair loops were compiled for: AVX-512 or AVX2 lanes
// (sph/simd_lanes.hpp), or the portable loops. Speed depends on it (docs/performance.md), so
// --version and the run header say which.
#include "exasph/sph/simd_lanes.hpp"

namespace exasph {
#if defined(EXASPH_SIMD_PAIRS) && defined(__AVX512F__)
inline constexpr const char* kPairLoopIsa = "AVX-512";
#elif defined(EXASPH_SIMD_PAIRS)
inline constexpr const char* kPairLoopIsa = "AVX2";
#else
inline constexpr const char* kPairLoopIsa = "portable";
#endif
} // namespace exasph
