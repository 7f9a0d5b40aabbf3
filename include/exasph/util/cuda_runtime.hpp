#pragma once
#include <string>

// The CUDA runtime as the rest of the code sees it: plain functions, defined in src/cuda/
// runtime.cu when the build has the CUDA backend (CMake EXASPH_CUDA) and in
// src/cuda/runtime_none.cpp otherwise. No CUDA header is needed to call them.
namespace exasph::cuda {

// Whether this build has the CUDA backend.
bool built();

// CUDA devices this process sees; 0 without a device or a driver (never throws).
int visible_devices();

// Makes device rank % visible_devices() this process's device and installs managed memory as
// the field memory (util/field_memory.hpp), before any particle exists. Returns the device's
// description for the run header. Throws Error when no device is visible.
std::string use_device(int rank);

// Why the last call reported no device ("" when it saw one): the driver's or runtime's words.
std::string no_device_reason();

} // namespace exasph::cuda
