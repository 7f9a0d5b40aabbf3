#pragma once
#include <cstdint>

#include <sys/resource.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace exasph {

// Peak resident set size of this process in bytes (Linux reports ru_maxrss in KiB).
inline std::uint64_t peak_rss_bytes() {
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    return static_cast<std::uint64_t>(ru.ru_maxrss) * 1024u;
}

// Large blocks (per-particle arrays, the step's scratch) are mapped pages that go back to the
// system when freed. glibc otherwise raises its mmap threshold after the first such free and
// serves later arrays from the heap, where freed memory stays resident: ~35 B/particle more
// peak memory at 10^6 particles. Call once at start-up.
inline void map_large_blocks() {
#if defined(__GLIBC__)
    mallopt(M_MMAP_THRESHOLD, 256 * 1024);
#endif
}

} // namespace exasph
