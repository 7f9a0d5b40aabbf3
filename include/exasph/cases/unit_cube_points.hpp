#pragma once
#include <cstdint>
#include <vector>

namespace exasph {

// side x side x layers points in [0, 1) x [0, 1) x [0, depth) with depth = layers / side (the
// unit cube when layers = side; a slab for the thin 2D-like cases), addressed by id: a
// cell-centred lattice, or a periodic glass block of block_side^3 points tiled side / block_side
// times along x and y and layers / block_side times along z. Cases map them into their boxes,
// so every rank can make exactly its share of the particles.
class UnitCubePoints {
  public:
    static UnitCubePoints lattice(std::uint64_t side, std::uint64_t layers = 0) {
        return UnitCubePoints(side, layers ? layers : side, 0, {});
    }
    // `block` holds block_side^3 positions in [0, 1)^3 (x, y, z interleaved); side and layers
    // are multiples of block_side.
    static UnitCubePoints tiled_glass(std::uint64_t side, std::uint64_t block_side,
                                      std::vector<double> block, std::uint64_t layers = 0) {
        return UnitCubePoints(side, layers ? layers : side, block_side, std::move(block));
    }

    std::uint64_t side() const { return side_; }
    std::uint64_t layers() const { return layers_; }
    std::uint64_t size() const { return side_ * side_ * layers_; }
    double spacing() const { return 1.0 / double(side_); }
    double depth() const { return double(layers_) / double(side_); }
    bool is_glass() const { return block_side_ > 0; }

    void position(std::uint64_t id, double& x, double& y, double& z) const {
        if (!is_glass()) {
            const std::uint64_t i = id / (side_ * layers_), j = (id / layers_) % side_;
            const std::uint64_t k = id % layers_;
            x = (double(i) + 0.5) / double(side_);
            y = (double(j) + 0.5) / double(side_);
            z = (double(k) + 0.5) / double(side_);
            return;
        }
        const std::uint64_t nb = block_side_ * block_side_ * block_side_;
        const std::uint64_t tiles = side_ / block_side_, tiles_z = layers_ / block_side_;
        const std::uint64_t t = id / nb, p = id % nb;
        const std::uint64_t ti = t / (tiles * tiles_z), tj = (t / tiles_z) % tiles;
        const std::uint64_t tk = t % tiles_z;
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
    UnitCubePoints(std::uint64_t side, std::uint64_t layers, std::uint64_t block_side,
                   std::vector<double> block)
        : side_(side), layers_(layers), block_side_(block_side), block_(std::move(block)) {}
    std::uint64_t side_, layers_, block_side_;
    std::vector<double> block_;
};

// The glass block used to tile a cube of `side` points per axis: the largest divisor of side
// between 8 and 25 (small enough to relax in seconds), or side itself.
inline std::uint64_t glass_block_side(std::uint64_t side) {
    for (std::uint64_t b = 25; b >= 8; --b)
        if (side % b == 0) return b;
    return side;
}

// The layers of a thin slab of side x side points: the smallest divisor of side from 8 up
// (a glass block of that side tiles the slab one block thick), or side itself.
inline std::uint64_t slab_layers(std::uint64_t side) {
    for (std::uint64_t b = 8; b <= 25 && b <= side; ++b)
        if (side % b == 0) return b;
    return side;
}

} // namespace exasph
