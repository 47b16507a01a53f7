#pragma once
// The fluid's physics, one source for every backend: the CPU backend (cpu_step.cpp, g++ as
// C++20) and the CUDA backend (cuda/device_fluid.cu, nvcc as C++17) include this header and
// keep only their loops and bookkeeping. Everything below is C++17, names no CUDA type, and
// marks what runs on a GPU too with HPCPLAN_HD (core/portable.hpp).
//   particle_fields.hpp    the per-particle fields, named once (X-macro) and ParticleView
//   kernels.hpp            poly6, spiky, viscosity (Müller et al.), Wendland C2
//   physics/params.hpp     FluidParams, Preset, MovingBox: the numbers the phases read
//   physics/equation_of_state.hpp   the seed's clamped gas law, Tait's equation and inverse
//   physics/push_out.hpp   the domain and the boxes as hard constraints; the frame check
//   physics/agitation.hpp  the seed's random kicks (SplitMix64, core/splitmix64.hpp)
//   physics/grid_walk.hpp  the neighbour grid's geometry and its 9-row walk
//   physics/phases.hpp     per-particle phases (densities, pressures, accelerations, Euler)
//   physics/solvers.hpp    the presets as lists of phases
#include "hpcplan/core/portable.hpp"
#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/sph/kernels.hpp"
#include "hpcplan/sph/particle_fields.hpp"
#include "hpcplan/sph/physics/agitation.hpp"
#include "hpcplan/sph/physics/equation_of_state.hpp"
#include "hpcplan/sph/physics/grid_walk.hpp"
#include "hpcplan/sph/physics/params.hpp"
#include "hpcplan/sph/physics/phases.hpp"
#include "hpcplan/sph/physics/push_out.hpp"
#include "hpcplan/sph/physics/solvers.hpp"
