# The CUDA backend (issue 18). ON by default where nvcc is found (PATH, CUDACXX or
# /usr/local/cuda), so that every build with a toolkit compiles the device code; without it the
# library exasph_cuda holds the stubs that say so (src/cuda/runtime_none.cpp).
include(CheckLanguage)
if(NOT CMAKE_CUDA_COMPILER AND NOT DEFINED ENV{CUDACXX} AND EXISTS /usr/local/cuda/bin/nvcc)
  set(CMAKE_CUDA_COMPILER /usr/local/cuda/bin/nvcc CACHE FILEPATH "CUDA compiler")
endif()
check_language(CUDA)
set(exasph_cuda_default OFF)
if(CMAKE_CUDA_COMPILER)
  set(exasph_cuda_default ON)
endif()
option(EXASPH_CUDA "Build the CUDA backend (--backend cuda)" ${exasph_cuda_default})

set(EXASPH_HAVE_CUDA 0)
set(EXASPH_CUDA_STATE off)
if(EXASPH_CUDA)
  if(NOT CMAKE_CUDA_COMPILER)
    message(FATAL_ERROR "EXASPH_CUDA is on but no nvcc was found (set CMAKE_CUDA_COMPILER)")
  endif()
  if(NOT DEFINED CMAKE_CUDA_ARCHITECTURES)
    set(CMAKE_CUDA_ARCHITECTURES 90) # H100/H200; override with -DCMAKE_CUDA_ARCHITECTURES=...
  endif()
  enable_language(CUDA)
  # CMake 3.25 does not know nvcc 13's C++20 flag.
  set(CMAKE_CUDA20_STANDARD_COMPILE_OPTION -std=c++20)
  set(CMAKE_CUDA20_EXTENSION_COMPILE_OPTION -std=c++20)
  # CMake 3.25's FindCUDAToolkit marks CUDA::nvToolsExt deprecated without checking that the
  # library exists, and CUDA 13 no longer ships it: the configure step fails. exasph does not
  # use it; an empty stand-in target lets Debian 12's stock CMake configure with CUDA 13.
  if(NOT TARGET CUDA::nvToolsExt)
    add_library(CUDA::nvToolsExt INTERFACE IMPORTED)
  endif()
  find_package(CUDAToolkit REQUIRED)
  add_library(exasph_cuda STATIC src/cuda/runtime.cu src/cuda/device_lists.cu
                                 src/cuda/passes.cu
                                 src/cuda/primitives.cu)
  set_target_properties(exasph_cuda PROPERTIES CUDA_STANDARD 20 CUDA_STANDARD_REQUIRED ON
                                               POSITION_INDEPENDENT_CODE ON)
  # Device-code warnings are errors; ptxas prints every kernel's registers, stack and spills
  # into the build log. Host-only flags (-march=native, -Wall) stay with the C++ targets.
  target_compile_options(exasph_cuda PRIVATE --expt-relaxed-constexpr "SHELL:-Werror all-warnings"
                                             -Xptxas=-v -Xcompiler=-fopenmp)
  target_link_libraries(exasph_cuda PUBLIC CUDA::cudart)
  set(EXASPH_HAVE_CUDA 1)
  set(EXASPH_CUDA_STATE "${CMAKE_CUDA_COMPILER_VERSION} sm_${CMAKE_CUDA_ARCHITECTURES}")
else()
  add_library(exasph_cuda STATIC src/cuda/runtime_none.cpp)
  set_target_properties(exasph_cuda PROPERTIES CXX_STANDARD 20)
endif()
target_include_directories(exasph_cuda PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include
                                              ${CMAKE_CURRENT_BINARY_DIR}/generated)
