#pragma once
// EXASPH_HD marks a function callable from host and device code. Physics kernels carry it so that
// the same function serves the OpenMP drivers and (later) the CUDA drivers.
#if defined(__CUDACC__)
#define EXASPH_HD __host__ __device__
#else
#define EXASPH_HD
#endif

// Forces inlining of small math helpers called inside `omp simd` loops: a call that is not
// inlined keeps the loop scalar.
#if defined(__GNUC__) || defined(__clang__)
#define EXASPH_INLINE inline __attribute__((always_inline))
#else
#define EXASPH_INLINE inline
#endif

// The same for a lambda (after its parameter list): GCC does not inline a large lambda called
// from two places, e.g. a pair loop's body (simd::for_each_step), whose sums then live in memory.
#if defined(__GNUC__) || defined(__clang__)
#define EXASPH_INLINE_LAMBDA __attribute__((always_inline))
#else
#define EXASPH_INLINE_LAMBDA
#endif

// Keeps a function out of its callers' loops (where inlining costs the loop registers).
#if defined(__GNUC__) || defined(__clang__)
#define EXASPH_NOINLINE __attribute__((noinline))
#else
#define EXASPH_NOINLINE
#endif
