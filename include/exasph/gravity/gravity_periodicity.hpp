#pragma once
#include <array>

#include "exasph/gravity/ewald_table.hpp"
#include "exasph/gravity/gravity_node.hpp"
#include "exasph/util/box.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// What the gravity walks need to know of the box: its minimum image and, when it is periodic, the
// Ewald table of its periods (physics.md §8). Requires a box open on every axis or periodic on
// every axis (a mixed box is refused with one line); the table is rebuilt only when the periods
// change (a periodic box keeps its size, so once per run).
class GravityPeriodicity {
  public:
    template <class T>
    void prepare(const Box<T>& box) {
        image_ = gravity_image(box);
        periodic_ = box.any_periodic();
        if (!periodic_) return;
        if (!(box.periodic[0] && box.periodic[1] && box.periodic[2]))
            throw input_error("self-gravity in a box periodic along some axes only is not "
                              "supported (the Ewald sum is for boxes periodic on every axis)",
                              true);
        const std::array<double, 3> len{image_.len[0], image_.len[1], image_.len[2]};
        if (table_.lengths() != len) table_ = EwaldTable(len);
    }

    bool periodic() const { return periodic_; }
    const GravityImage& image() const { return image_; }
    // Requires periodic().
    EwaldTable::View ewald() const { return table_.view(); }

  private:
    GravityImage image_{Box<double>{{0, 0, 0}, {1, 1, 1}, {false, false, false}}};
    bool periodic_ = false;
    EwaldTable table_;
};

} // namespace exasph
