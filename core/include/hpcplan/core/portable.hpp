#pragma once
// Functions that run on the host and, compiled by nvcc, on a GPU too: the fluid's physics is
// written once (sph/physics/*.hpp) and included by the CPU backend (g++, C++20) and the CUDA
// backend (nvcc, C++17). Headers that use this macro stay C++17 and name no CUDA type.
#if defined(__CUDACC__)
#define HPCPLAN_HD __host__ __device__
#else
#define HPCPLAN_HD
#endif
