// Fuzz harness: the checkpoint reader (--restart FILE). Input: a mode byte, then either the
// bytes of a file (even mode: damaged bytes, which the seal must refuse before HDF5 reads
// them) or a recipe of edits (fuzz/h5_recipe.hpp) to one of the real checkpoints in
// fuzz/bases/checkpoint, sealed again after the edit (odd mode: what lies behind the seal, as
// if exasph had written it). The file must be read into a configuration that validate_config
// accepts and a state a run can continue from, or refused with an exasph::Error.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "exasph/config/validate.hpp"
#include "exasph/io/checkpoint.hpp"
#include "fuzz_support.hpp"
#include "h5_recipe.hpp"
#include "recipe_names.hpp"

namespace {

void check_accepted(const exasph::Checkpoint<double>& cp) {
    const auto& ic = cp.ic;
    bool ok = std::isfinite(ic.eos.gamma) && std::isfinite(ic.eos.c0) && ic.dt0 > 0 &&
              std::isfinite(ic.dt0) && std::isfinite(cp.rs.time) && cp.rs.step >= 0 &&
              std::isfinite(cp.rs.dt_m1) && ic.particles.size() > 0;
    for (int d = 0; d < 3; ++d)
        ok = ok && std::isfinite(ic.box.lo[d]) && std::isfinite(ic.box.hi[d]) &&
             ic.box.lo[d] < ic.box.hi[d];
    if (ok) return;
    std::fprintf(stderr,
                 "fuzz finding: checkpoint accepted with gamma %g dt0 %g time %g step %lld\n",
                 ic.eos.gamma, ic.dt0, cp.rs.time, (long long)cp.rs.step);
    std::abort();
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    exasph::fuzz::start_mpi_once();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const auto bases = exasph::fuzz::base_files(EXASPH_FUZZ_BASES "/checkpoint");
    static const auto names = exasph::fuzz::recipe_names();
    if (size == 0) return 0;
    std::string path;
    if (data[0] % 2 == 0) {
        path = exasph::fuzz::scratch_file(data + 1, size - 1, "-checkpoint.h5");
    } else {
        path = exasph::fuzz::scratch_file(data, 0, "-checkpoint.h5");
        exasph::fuzz::RecipeReader recipe(data + 1, size - 1);
        exasph::fuzz::apply_recipe(bases, path, {"/", "/state", "/domain"}, names, recipe);
        exasph::seal_file(path, MPI_COMM_WORLD);
    }
    exasph::fuzz::expect_clear_refusal([&] {
        exasph::Config cfg;
        check_accepted(exasph::read_checkpoint<double>(path, cfg, MPI_COMM_WORLD));
        exasph::validate_config(cfg);
    });
    return 0;
}
