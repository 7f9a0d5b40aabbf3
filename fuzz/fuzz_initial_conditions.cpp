// Fuzz harness: the HDF5 initial-conditions reader (--init FILE.h5, docs/file-format.md).
// Input: a recipe of edits (fuzz/h5_recipe.hpp) to one of the real files in
// fuzz/bases/initial_conditions. The edited file must be read into initial conditions a run can
// start from, or refused with an exasph::Error.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "exasph/io/initial_conditions_file.hpp"
#include "fuzz_support.hpp"
#include "h5_recipe.hpp"
#include "recipe_names.hpp"

namespace {

// What a successful read promises the run (else a finding: bad input accepted silently).
void check_accepted(const exasph::InitialConditions<double>& ic) {
    bool ok = ic.eos.gamma > 1 && std::isfinite(ic.eos.gamma) && ic.dt0 > 0 &&
              std::isfinite(ic.dt0) && std::isfinite(ic.t_end) && ic.particles.size() > 0;
    for (int d = 0; d < 3; ++d)
        ok = ok && std::isfinite(ic.box.lo[d]) && std::isfinite(ic.box.hi[d]) &&
             ic.box.lo[d] < ic.box.hi[d];
    if (ok) return;
    std::fprintf(stderr,
                 "fuzz finding: initial conditions accepted with gamma %g dt0 %g t_end "
                 "%g n %zu\n",
                 ic.eos.gamma, ic.dt0, ic.t_end, ic.particles.size());
    std::abort();
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    exasph::fuzz::start_mpi_once();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const auto bases = exasph::fuzz::base_files(EXASPH_FUZZ_BASES "/initial_conditions");
    static const auto names = exasph::fuzz::recipe_names();
    const std::string path = exasph::fuzz::scratch_file(data, 0, "-ic.h5");
    exasph::fuzz::RecipeReader recipe(data, size);
    exasph::fuzz::apply_recipe(bases, path, {"/", "/Step#2"}, names, recipe);
    exasph::fuzz::expect_clear_refusal(
        [&] { check_accepted(exasph::read_initial_conditions<double>(path, MPI_COMM_WORLD)); });
    return 0;
}
