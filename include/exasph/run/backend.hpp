#pragma once
#include <string>

#include "exasph/util/mpi.hpp"

#include "exasph/build_info.hpp"
#include "exasph/config/config.hpp"
#include "exasph/sph/launch.hpp"
#include "exasph/util/cuda_runtime.hpp"
#include "exasph/util/error.hpp"
#if EXASPH_HAVE_CUDA
#include "exasph/sph/cuda_launcher.hpp"
#endif

namespace exasph {

// The backend of a run and the header's line about it.
struct BackendPick {
    Backend backend = Backend::openmp;
    std::string line;
};

// --backend: cpu, cuda (an error with one line and exit 2 where this build has no CUDA backend
// or a rank sees no device) or auto (cuda where every rank sees a device, else cpu, saying why).
// Chosen once, before any particle exists: the CUDA backend selects each rank's device (rank
// modulo the visible devices) and puts the particle fields in managed memory. All ranks agree
// (one collective at start-up).
inline BackendPick pick_backend(BackendChoice choice, MPI_Comm comm) {
    if (choice == BackendChoice::cpu) return {Backend::openmp, "cpu (OpenMP)"};
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    int sees_device = cuda::visible_devices() > 0 ? 1 : 0;
    MPI_Allreduce(MPI_IN_PLACE, &sees_device, 1, MPI_INT, MPI_MIN, comm);
    if (!sees_device) {
        const std::string why = cuda::built() ? "no CUDA device is visible on every rank (" +
                                                    cuda::no_device_reason() + ")"
                                              : cuda::no_device_reason();
        if (choice == BackendChoice::cuda)
            throw input_error("--backend cuda: " + why + "; use --backend cpu or auto", true);
        return {Backend::openmp, "cpu (OpenMP; auto: " + why + ")"};
    }
    return {Backend::cuda, "cuda, " + cuda::use_device(rank) +
                               (choice == BackendChoice::automatic ? " (auto)" : "")};
}

} // namespace exasph
