#pragma once
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "exasph/particles/field_list.hpp"
#include "exasph/util/error.hpp"
#include "exasph/util/field_memory.hpp"

namespace exasph {

// Structure of arrays: one FieldArray (util/field_memory.hpp: host, or memory a device reads too)
// per field of kFieldTable, plus a persistent 64-bit id.
// Optional fields (role kOptional: needed only by some cases or options) hold no memory until
// enabled; code that iterates fields for a set asks the set (fields()) for the enabled ones.
// Invariant: every enabled field vector and `id` have size() elements; disabled ones are empty.
// The is_narrow fields are stored in single precision by default (narrow_single()) or, for
// `--precision double`, in T like the others (set_narrow_single).
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
    FieldArray<T>& operator[](Field f) { return fields_[static_cast<std::size_t>(f)]; }
    const FieldArray<T>& operator[](Field f) const { return fields_[static_cast<std::size_t>(f)]; }
    T* data(Field f) { return (*this)[f].data(); }
    const T* data(Field f) const { return (*this)[f].data(); }
    // The is_narrow fields in their storage type N: float when narrow_single(), else T.
    template <class N>
    N* narrow_as(Field f) {
        return const_cast<N*>(std::as_const(*this).template narrow_as<N>(f));
    }
    template <class N>
    const N* narrow_as(Field f) const {
        const auto k = static_cast<std::size_t>(f);
        if constexpr (std::is_same_v<N, float>)
            if (narrow_single_) return narrow_[k].data();
        if constexpr (std::is_same_v<N, T>)
            if (!narrow_single_) return fields_[k].data();
        throw Error("particle set: field " + std::string(field_info(f).name) +
                    " is not stored in the precision asked for");
    }
    // Single-precision storage (is_narrow), the default.
    float* narrow(Field f) { return narrow_as<float>(f); }
    const float* narrow(Field f) const { return narrow_as<float>(f); }
    bool narrow_single() const { return narrow_single_; }
    // Whether f is in the float storage (narrow()) rather than in T (data()).
    bool stored_single(Field f) const { return narrow_single_ && is_narrow(f); }
    // Moves the is_narrow fields to single precision (true) or to T (false), keeping the values.
    void set_narrow_single(bool single) {
        if (single == narrow_single_) return;
        for (std::size_t k = 0; k < kNumFields; ++k) {
            if (!is_narrow(static_cast<Field>(k))) continue;
            if (single) {
                narrow_[k].assign(fields_[k].begin(), fields_[k].end());
                FieldArray<T>().swap(fields_[k]);
            } else {
                fields_[k].assign(narrow_[k].begin(), narrow_[k].end());
                FieldArray<float>().swap(narrow_[k]);
            }
        }
        narrow_single_ = single;
    }
    // Either storage, as double (I/O, halo packing, tests).
    double value(Field f, std::size_t i) const {
        return stored_single(f) ? double(narrow_[static_cast<std::size_t>(f)][i])
                                : double(data(f)[i]);
    }
    void set_value(Field f, std::size_t i, double v) {
        if (stored_single(f))
            narrow_[static_cast<std::size_t>(f)][i] = float(v);
        else
            data(f)[i] = T(v);
    }

    // The fields that move with a particle when the domain sorts or migrates it: the state, and
    // with block time steps (carry(kState | kDerived)) the derived fields too, since an inactive
    // particle's density, pressure, IAD matrix and forces of an earlier sub-step are read by its
    // active neighbours (sim/block_clock.hpp).
    std::uint8_t carried() const { return carried_; }
    void carry(std::uint8_t roles) { carried_ = roles; }

    // Reorders the carried fields (and the ids): new[i] = old[order[i]]; the set then has
    // order.size() particles (a shorter order drops particles). The other fields are recomputed
    // before they are read: they are only resized.
    void permute(const std::vector<std::uint32_t>& order) {
        if (permute_in_place(order)) return;
        FieldArray<T> scratch(order.size());
        FieldArray<float> narrow_scratch;
        for (Field fld : fields(carried_)) {
            if (stored_single(fld)) {
                auto& f = narrow_[static_cast<std::size_t>(fld)];
                gather(f, order, narrow_scratch);
                f.swap(narrow_scratch);
                continue;
            }
            auto& f = (*this)[fld];
            gather(f, order, scratch);
            f.swap(scratch);
        }
        FieldArray<std::uint64_t> new_id(order.size());
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

    FieldArray<std::uint64_t> id; // where the fields are: a device checks it too

  private:
    // A permutation of the same particles that moves few of them (between two sub-steps of block
    // time steps most particles keep their place): only the moved entries are copied, through a
    // scratch of their size. Returns false (nothing done) if more than a quarter move.
    bool permute_in_place(const std::vector<std::uint32_t>& order) {
        if (order.size() != size()) return false;
        std::vector<std::uint32_t> moved;
        for (std::uint32_t i = 0; i < order.size(); ++i)
            if (order[i] != i) moved.push_back(i);
        if (moved.size() > order.size() / 4) return false;
        auto apply = [&](auto& f, auto& scratch) {
            scratch.resize(moved.size());
            for (std::size_t k = 0; k < moved.size(); ++k) scratch[k] = f[order[moved[k]]];
            for (std::size_t k = 0; k < moved.size(); ++k) f[moved[k]] = scratch[k];
        };
        std::vector<T> wide;
        std::vector<float> single;
        std::vector<std::uint64_t> ids;
        for (Field fld : fields(carried_)) {
            if (stored_single(fld))
                apply(narrow_[static_cast<std::size_t>(fld)], single);
            else
                apply((*this)[fld], wide);
        }
        apply(id, ids);
        return true;
    }

    // A field's array, in whichever precision it is stored.
    void resize_storage(Field f, std::size_t n) {
        const auto k = static_cast<std::size_t>(f);
        stored_single(f) ? narrow_[k].resize(n) : fields_[k].resize(n);
    }
    std::size_t storage_size(Field f) const {
        const auto k = static_cast<std::size_t>(f);
        return stored_single(f) ? narrow_[k].size() : fields_[k].size();
    }

    template <class Array>
    static void gather(const Array& src, const std::vector<std::uint32_t>& order, Array& dst) {
        dst.resize(order.size());
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < order.size(); ++i) dst[i] = src[order[i]];
    }

    std::array<FieldArray<T>, kNumFields> fields_;
    std::array<FieldArray<float>, kNumFields> narrow_; // the is_narrow fields when single
    std::array<bool, kNumFields> optional_on_{};
    bool narrow_single_ = true;
    std::uint8_t carried_ = kState;
};

} // namespace exasph
