#pragma once
// The instruction set the CPU pair loops were compiled for: the name of the lane set they use
// (simd::Native, sph/simd_isa.hpp), or "portable" where the build has none. Speed depends on it
// (docs/performance.md), so --version and the run header say which.
#include "exasph/sph/simd_isa.hpp"

namespace exasph {
#ifdef EXASPH_SIMD_LANES
inline constexpr const char* kPairLoopIsa = simd::Native::kName;
#else
inline constexpr const char* kPairLoopIsa = "portable";
#endif
} // namespace exasph
