// Issue 21: the seals inside a step (sim/step_seals.hpp) find a bit that flips after a phase
// made a value and before its readers are done, in the state and in derived fields stored in
// single precision, and nothing when the step only does what it should.
#include <cstdint>
#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "exasph/sim/state_guard.hpp"
#include "exasph/sim/step_seals.hpp"

using namespace exasph;

namespace {
ParticleSet<double> particles(std::size_t n) {
    ParticleSet<double> ps;
    ps.resize(n);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.1, 0.9);
    for (std::size_t i = 0; i < n; ++i) {
        ps.id[i] = 10 + 3 * i;
        for (const auto& info : kFieldTable)
            if (ps.enabled(info.field)) ps.set_value(info.field, i, u(rng));
    }
    return ps;
}

void flip(ParticleSet<double>& ps, Field f, std::size_t i, int bit) {
    if (ps.stored_single(f)) {
        std::uint32_t b;
        std::memcpy(&b, &ps.narrow(f)[i], 4);
        b ^= 1u << bit;
        std::memcpy(&ps.narrow(f)[i], &b, 4);
    } else {
        std::uint64_t b;
        std::memcpy(&b, &ps[f][i], 8);
        b ^= 1ull << bit;
        std::memcpy(&ps[f][i], &b, 8);
    }
}

// Runs the phase ends of one step over ps, calling corrupt(phase) after each (the fault
// injection's place); returns what the seals found.
template <class Corrupt>
std::string step(ParticleSet<double>& ps, std::size_t n, Corrupt corrupt) {
    StepSeals<double> seals;
    seals.begin(5);
    std::string found;
    auto note = [&](std::string s) {
        if (found.empty()) found = std::move(s);
    };
    for (std::size_t p = 0; p < kNumPhases; ++p) {
        if (p == kUpdate) note(seals.before_update(ps, n));
        if (p == kSmoothingLength) note(seals.before_h_update(ps, n));
        if (p == kUpdate) ps.set_value(Field::x, 0, ps.value(Field::x, 0) + 0.01); // the update
        if (p == kSmoothingLength) ps.set_value(Field::h, 1, ps.value(Field::h, 1) * 1.01);
        note(seals.phase_ended(p, ps, n));
        if (p == kDiagnostics) {
            StateGuard<double> guard;
            note(seals.at_guard_seal(guard.seal(ps, n)));
        }
        corrupt(p);
    }
    return found;
}
} // namespace

TEST(StepSeals, AStepThatOnlyDoesItsWorkIsClean) {
    auto ps = particles(300);
    EXPECT_EQ(step(ps, 300, [](std::size_t) {}), "");
}

TEST(StepSeals, FlipsBetweenProducerAndReadersAreFound) {
    struct Case {
        Field field;
        std::size_t phase; // the flip follows the end of this phase
        const char* found;
    };
    const Case cases[] = {
        {Field::vx, kTimeStep, "the state changed between the sync and the update"},
        {Field::ax, kGravity, "the accelerations changed between the gravity phase and the update"},
        {Field::rho, kIad, "the density pass's fields changed before the h update had read them"},
        {Field::nc, kUpdate, "the density pass's fields changed before the h update had read them"},
        {Field::c11, kMomentumEnergy, "the IAD matrices changed before the h update ended"},
        {Field::h, kUpdate, "the state changed between the update and the h update"},
        {Field::du_m1, kSmoothingLength,
         "the state changed between the h update and the end of the step"},
    };
    for (const auto& c : cases) {
        auto ps = particles(300);
        ASSERT_TRUE(c.field != Field::rho || ps.stored_single(Field::rho)); // float storage too
        const std::string found = step(ps, 300, [&](std::size_t p) {
            if (p == c.phase) flip(ps, c.field, 123, 7); // a low mantissa bit
        });
        EXPECT_EQ(found, c.found) << field_info(c.field).name;
    }
}
