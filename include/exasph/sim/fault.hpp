#pragma once
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "exasph/particles/particle_set.hpp"
#include "exasph/sim/phases.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Fault injection for the silent-data-corruption tests (issue 8).

// --inject-fault STEP:FIELD:ID:BIT[:PHASE]: flip bit BIT (0 = least significant) of FIELD of
// the particle with id ID, once: at the start of step STEP (before the state is verified), or
// with PHASE (a name of sim/phases.hpp) when that phase of step STEP ends, so that derived
// fields (rho, p, c, ax, du, ...) are hit between the passes that make and use them (issue 21's
// fault map). A field stored in single precision has bits 0..31.
struct FaultSpec {
    std::int64_t step = -1; // < 0: none
    Field field = Field::x;
    std::uint64_t id = 0;
    int bit = 0;
    int phase = -1; // < 0: the start of the step
};

// The phase of the name, or -1.
inline int phase_from_name(const std::string& name) {
    for (std::size_t p = 0; p < kNumPhases; ++p)
        if (kPhaseNames[p] == name) return int(p);
    return -1;
}

inline FaultSpec parse_fault(const std::string& text) {
    FaultSpec f;
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (std::size_t i = 0; i <= text.size(); ++i)
        if (i == text.size() || text[i] == ':') {
            parts.push_back(text.substr(start, i - start));
            start = i + 1;
        }
    const std::string usage = "--inject-fault " + text + ": expected STEP:FIELD:ID:BIT[:PHASE]";
    if (parts.size() != 4 && parts.size() != 5) throw input_error(usage, true);
    bool found = false;
    for (const auto& info : kFieldTable)
        if (info.name == parts[1]) f.field = info.field, found = true;
    // (An optional field the run does not carry is refused when the fault is injected.)
    if (!found)
        throw input_error(usage + " with FIELD a particle field (x, u, rho, ax, ...)", true);
    if (parts.size() == 5 && (f.phase = phase_from_name(parts[4])) < 0)
        throw input_error(usage + " with PHASE one of the step's phases (sync, density, ...)",
                          true);
    try {
        std::size_t used = 0;
        f.step = std::stoll(parts[0], &used);
        if (used != parts[0].size() || f.step < 1) throw std::invalid_argument("step");
        f.id = std::stoull(parts[2], &used);
        if (used != parts[2].size()) throw std::invalid_argument("id");
        f.bit = std::stoi(parts[3], &used);
        if (used != parts[3].size() || f.bit < 0 || f.bit >= 64) throw std::invalid_argument("b");
    } catch (const std::exception&) {
        throw input_error(usage + " (STEP >= 1, BIT in 0..63 for double)", true);
    }
    return f;
}

// Flips bit `bit` of v (modulo its width).
template <class V>
void flip_bit(V& v, int bit) {
    static_assert(sizeof(V) == 8 || sizeof(V) == 4);
    if constexpr (sizeof(V) == 8) {
        std::uint64_t b;
        std::memcpy(&b, &v, 8);
        b ^= std::uint64_t(1) << (bit % 64);
        std::memcpy(&v, &b, 8);
    } else {
        std::uint32_t b;
        std::memcpy(&b, &v, 4);
        b ^= std::uint32_t(1) << (bit % 32);
        std::memcpy(&v, &b, 4);
    }
}

// Flips the bit in this rank's copy of the particle, if it owns it; returns whether it did.
template <class T>
bool inject_fault(ParticleSet<T>& ps, std::size_t n, const FaultSpec& f) {
    static_assert(sizeof(T) == 8 || sizeof(T) == 4);
    if (!ps.enabled(f.field))
        throw input_error("--inject-fault: this run carries no field " +
                              std::string(field_info(f.field).name),
                          true);
    for (std::size_t i = 0; i < n; ++i) {
        if (ps.id[i] != f.id) continue;
        if (ps.stored_single(f.field))
            flip_bit(ps.narrow(f.field)[i], f.bit);
        else
            flip_bit(ps[f.field][i], f.bit);
        return true;
    }
    return false;
}

} // namespace exasph
