#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "exasph/io/gadget_ic.hpp"
#include "exasph/io/gadget_layout.hpp"
#include "exasph/io/h5_file.hpp"
#include "exasph/io/initial_conditions_file.hpp"
#include "exasph/particles/field_list.hpp"

namespace exasph {

// Where a snapshot keeps its particles, in either format version: 2 (GADGET layout, /PartType0:
// io/gadget_layout.hpp) or 1 (the last Step#N group, one 1-D dataset per field, named as the
// field). Reads this rank's rows of a field, named as exasph names it.
class SnapshotParticles {
  public:
    SnapshotParticles(const h5::File& file, const h5::Group& root)
        : gadget_(is_gadget_layout(root)),
          group_(gadget_ ? std::string("/PartType0") : particle_group_name(root)),
          g_(file, group_, false), time_group_(file, gadget_ ? "/Header" : group_, false) {
        n_ = gadget_ ? gadget::particle_counts(time_group_)[0] : h5::dataset_length(g_, "x");
    }
    std::uint64_t size() const { return n_; }
    double time() const {
        const char* name = gadget_ ? "Time" : "time";
        return h5::has_attribute(time_group_, name)
                   ? h5::read_attribute_doubles(time_group_, name).at(0)
                   : 0.0;
    }
    // The field's dataset, or "" when the file has none (or exasph has no such field).
    std::string dataset(const std::string& field) const {
        if (!gadget_) return h5::has_link(g_, field) ? field : "";
        const auto f = field_named(field);
        if (!f) return "";
        const std::string name = gadget_column(*f).dataset.name;
        return h5::has_link(g_, name) ? name : "";
    }
    std::string unit(const std::string& field) const {
        const std::string attr = "unit:" + dataset(field);
        return h5::has_attribute(g_, attr) ? h5::read_attribute_string(g_, attr) : "";
    }
    std::vector<double> read(const std::string& field, std::uint64_t lo,
                             std::uint64_t count) const {
        if (!gadget_) return h5::read_doubles(g_, field, lo, count);
        return read_gadget_field(g_, *field_named(field), n_, lo, count);
    }
    const std::string& group() const { return group_; }

  private:
    static std::optional<Field> field_named(const std::string& name) {
        for (const auto& f : kFieldTable)
            if (f.name == name) return f.field;
        return std::nullopt;
    }
    bool gadget_;
    std::string group_;
    h5::Group g_, time_group_;
    std::uint64_t n_ = 0;
};

} // namespace exasph
