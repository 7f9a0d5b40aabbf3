#pragma once
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "exasph/particles/field_list.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Structure of arrays: one vector per field of kFieldTable, plus a persistent 64-bit id.
// Optional fields (role kOptional: needed only by some cases or options) hold no memory until
// enabled; code that iterates fields for a set asks the set (fields()) for the enabled ones.
// Invariant: every enabled field vector and `id` have size() elements; disabled ones are empty.
template <class T>
class ParticleSet {
  public:
    using value_type = T;

    std::size_t size() const { return id.size(); }

    void resize(std::size_t n) {
        for (std::size_t f = 0; f < kNumFields; ++f)
            if (enabled(static_cast<Field>(f))) resize_storage(static_cast<Field>(f), n);
        id.resize(n);
    }

    bool enabled(Field f) const {
        return !(field_info(f).roles & kOptional) || optional_on_[static_cast<std::size_t>(f)];
    }
    // Allocates an optional field (zero-filled).
    void enable(Field f) {
        if (enabled(f)) return;
        optional_on_[static_cast<std::size_t>(f)] = true;
        resize_storage(f, 0); // zero-filled, whatever the vector held
        resize_storage(f, size());
    }
    // Allocates the optional fields with any of `roles` (e.g. kHaloGrad: the velocity gradient).
    void enable(std::uint8_t roles) {
        for (const auto& info : kFieldTable)
            if ((info.roles & kOptional) && (info.roles & roles)) enable(info.field);
    }

    // The enabled fields carrying any of `roles`, in table order.
    std::vector<Field> fields(std::uint8_t roles) const {
        std::vector<Field> out;
        for (const auto& info : kFieldTable)
            if ((info.roles & roles) && enabled(info.field)) out.push_back(info.field);
        return out;
    }

    // Fields in the working precision T (not is_narrow).
    std::vector<T>& operator[](Field f) { return fields_[static_cast<std::size_t>(f)]; }
    const std::vector<T>& operator[](Field f) const { return fields_[static_cast<std::size_t>(f)]; }
    T* data(Field f) { return (*this)[f].data(); }
    const T* data(Field f) const { return (*this)[f].data(); }
    // Fields stored in single precision (is_narrow).
    float* narrow(Field f) { return narrow_[static_cast<std::size_t>(f)].data(); }
    const float* narrow(Field f) const { return narrow_[static_cast<std::size_t>(f)].data(); }
    // Either storage, as double (I/O, halo packing, tests).
    double value(Field f, std::size_t i) const {
        return is_narrow(f) ? double(narrow(f)[i]) : double(data(f)[i]);
    }
    void set_value(Field f, std::size_t i, double v) {
        if (is_narrow(f))
            narrow(f)[i] = float(v);
        else
            data(f)[i] = T(v);
    }

    // Reorders all fields whose role matches `roles` (and the ids): new[i] = old[order[i]]; the
    // set then has order.size() particles (a shorter order drops particles). Derived fields are
    // recomputed every step: they are only resized.
    void permute(const std::vector<std::uint32_t>& order, std::uint8_t roles = kState) {
        std::vector<T> scratch(order.size());
        for (Field fld : fields(roles)) {
            if (is_narrow(fld)) throw Error("particle set: narrow fields are never permuted");
            auto& f = (*this)[fld];
            gather(f, order, scratch);
            f.swap(scratch);
        }
        std::vector<std::uint64_t> new_id(order.size());
        gather(id, order, new_id);
        id.swap(new_id);
        resize(order.size());
    }

    // Checks the invariants of the state: sizes agree, state values finite, m > 0, h > 0.
    // Throws Error naming the first offending particle.
    void validate() const {
        for (std::size_t f = 0; f < kNumFields; ++f)
            if (enabled(static_cast<Field>(f)) && storage_size(static_cast<Field>(f)) != size())
                throw Error("particle set: field sizes disagree");
        for (Field fld : fields(kState)) {
            const auto& f = (*this)[fld];
            for (std::size_t i = 0; i < size(); ++i)
                if (!std::isfinite(f[i]))
                    throw Error("particle " + std::to_string(id[i]) + ": field " +
                                std::string(field_info(fld).name) + " is not finite");
        }
        for (Field f : {Field::m, Field::h}) {
            const auto& v = (*this)[f];
            for (std::size_t i = 0; i < size(); ++i)
                if (!(v[i] > T(0)))
                    throw Error("particle " + std::to_string(id[i]) + ": field " +
                                std::string(field_info(f).name) + " must be positive");
        }
    }

    std::vector<std::uint64_t> id;

  private:
    // A field's array, in whichever precision it is stored.
    void resize_storage(Field f, std::size_t n) {
        const auto k = static_cast<std::size_t>(f);
        is_narrow(f) ? narrow_[k].resize(n) : fields_[k].resize(n);
    }
    std::size_t storage_size(Field f) const {
        const auto k = static_cast<std::size_t>(f);
        return is_narrow(f) ? narrow_[k].size() : fields_[k].size();
    }

    template <class V>
    static void gather(const std::vector<V>& src, const std::vector<std::uint32_t>& order,
                       std::vector<V>& dst) {
        dst.resize(order.size());
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < order.size(); ++i) dst[i] = src[order[i]];
    }

    std::array<std::vector<T>, kNumFields> fields_;
    std::array<std::vector<float>, kNumFields> narrow_; // used for the is_narrow fields only
    std::array<bool, kNumFields> optional_on_{};
};

} // namespace exasph
