#pragma once
#include <cstdint>
#include <vector>

namespace exasph {

// side^3 points in the unit cube [0, 1)^3, addressed by id: a cell-centred lattice, or a periodic
// glass block of block_side^3 points tiled (side / block_side)^3 times. Cases map them into
// their boxes, so every rank can make exactly its share of the particles.
class UnitCubePoints {
  public:
    static UnitCubePoints lattice(std::uint64_t side) { return UnitCubePoints(side, 0, {}); }
    // `block` holds block_side^3 positions in [0, 1)^3 (x, y, z interleaved).
    static UnitCubePoints tiled_glass(std::uint64_t side, std::uint64_t block_side,
                                      std::vector<double> block) {
        return UnitCubePoints(side, block_side, std::move(block));
    }

    std::uint64_t side() const { return side_; }
    std::uint64_t size() const { return side_ * side_ * side_; }
    double spacing() const { return 1.0 / double(side_); }
    bool is_glass() const { return block_side_ > 0; }

    void position(std::uint64_t id, double& x, double& y, double& z) const {
        if (!is_glass()) {
            const std::uint64_t i = id / (side_ * side_), j = (id / side_) % side_, k = id % side_;
            x = (double(i) + 0.5) / double(side_);
            y = (double(j) + 0.5) / double(side_);
            z = (double(k) + 0.5) / double(side_);
            return;
        }
        const std::uint64_t nb = block_side_ * block_side_ * block_side_;
        const std::uint64_t tiles = side_ / block_side_;
        const std::uint64_t t = id / nb, p = id % nb;
        const std::uint64_t ti = t / (tiles * tiles), tj = (t / tiles) % tiles, tk = t % tiles;
        x = (double(ti) + block_[3 * p]) / double(tiles);
        y = (double(tj) + block_[3 * p + 1]) / double(tiles);
        z = (double(tk) + block_[3 * p + 2]) / double(tiles);
    }

    // This rank's share of the ids.
    void share(int rank, int nranks, std::uint64_t& first, std::uint64_t& last) const {
        first = size() * std::uint64_t(rank) / std::uint64_t(nranks);
        last = size() * std::uint64_t(rank + 1) / std::uint64_t(nranks);
    }

  private:
    UnitCubePoints(std::uint64_t side, std::uint64_t block_side, std::vector<double> block)
        : side_(side), block_side_(block_side), block_(std::move(block)) {}
    std::uint64_t side_, block_side_;
    std::vector<double> block_;
};

// The glass block used to tile a cube of `side` points per axis: the largest divisor of side
// between 8 and 25 (small enough to relax in seconds), or side itself.
inline std::uint64_t glass_block_side(std::uint64_t side) {
    for (std::uint64_t b = 25; b >= 8; --b)
        if (side % b == 0) return b;
    return side;
}

} // namespace exasph
