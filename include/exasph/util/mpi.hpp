#pragma once
// MPI for the whole code: the real one, or in a build without MPI (CMake EXASPH_MPI=OFF) the
// single-rank stand-in of util/serial_mpi.hpp. Include this, never <mpi.h> directly.
#include "exasph/build_info.hpp"
#if EXASPH_HAVE_MPI
#include <mpi.h>
#else
#include "exasph/util/serial_mpi.hpp"
#endif
