#pragma once
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

#include "exasph/util/checksum.hpp"

namespace exasph {

// The glass cache's file: a block's points in a small binary file that every build reads and
// writes (with or without HDF5), so a build without HDF5 makes each glass once too. Layout,
// little-endian as the machine writes it (a cache, never moved between machines):
//   8 bytes "EXGLASS1", uint64 block side, double ng0, uint64 point count n,
//   3n doubles (x, y, z of point 0, 1, ... in [0, 1)^3), uint64 hash of all the above.
// A file that does not match (short, other side or ng0, wrong hash) is not used: the block is
// made again and the file replaced.
inline constexpr char kGlassCacheMagic[8] = {'E', 'X', 'G', 'L', 'A', 'S', 'S', '1'};

inline std::uint64_t glass_cache_hash(std::uint64_t side, double ng0,
                                      const std::vector<double>& points) {
    HashChain h(side);
    h.add_float(ng0).add(points.size());
    for (double p : points) h.add_float(p);
    return h.value();
}

// The points of a cached block, or nothing where the file is absent or does not match.
inline std::optional<std::vector<double>> read_glass_cache(const std::string& path,
                                                           std::uint64_t side, double ng0) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    char magic[8];
    std::uint64_t file_side = 0, n = 0, hash = 0;
    double file_ng0 = 0;
    in.read(magic, 8);
    in.read(reinterpret_cast<char*>(&file_side), 8);
    in.read(reinterpret_cast<char*>(&file_ng0), 8);
    in.read(reinterpret_cast<char*>(&n), 8);
    if (!in || std::memcmp(magic, kGlassCacheMagic, 8) != 0 || file_side != side ||
        file_ng0 != ng0 || n != side * side * side)
        return std::nullopt;
    std::vector<double> points(3 * n);
    in.read(reinterpret_cast<char*>(points.data()), std::streamsize(8 * points.size()));
    in.read(reinterpret_cast<char*>(&hash), 8);
    if (!in || in.peek() != EOF || hash != glass_cache_hash(side, ng0, points)) return std::nullopt;
    return points;
}

// Writes the file under a temporary name and renames it into place, so that two runs making
// the same block at once, or a run killed while writing, never leave a partial file.
inline bool write_glass_cache(const std::string& path, std::uint64_t side, double ng0,
                              const std::vector<double>& points) {
    const std::string tmp = path + ".tmp" + std::to_string(::getpid());
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        const std::uint64_t n = points.size() / 3, hash = glass_cache_hash(side, ng0, points);
        out.write(kGlassCacheMagic, 8);
        out.write(reinterpret_cast<const char*>(&side), 8);
        out.write(reinterpret_cast<const char*>(&ng0), 8);
        out.write(reinterpret_cast<const char*>(&n), 8);
        out.write(reinterpret_cast<const char*>(points.data()), std::streamsize(8 * points.size()));
        out.write(reinterpret_cast<const char*>(&hash), 8);
        if (!out.flush()) {
            std::error_code ec;
            std::filesystem::remove(tmp, ec);
            return false;
        }
    }
    return std::rename(tmp.c_str(), path.c_str()) == 0;
}

} // namespace exasph
