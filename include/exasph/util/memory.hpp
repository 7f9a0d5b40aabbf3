#pragma once
#include <cstdint>

#include <sys/resource.h>

namespace exasph {

// Peak resident set size of this process in bytes (Linux reports ru_maxrss in KiB).
inline std::uint64_t peak_rss_bytes() {
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    return static_cast<std::uint64_t>(ru.ru_maxrss) * 1024u;
}

} // namespace exasph
