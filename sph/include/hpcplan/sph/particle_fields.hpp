#pragma once
// The fluid's per-particle fields, named once. HPCPLAN_SPH_PARTICLE_FIELDS(X) expands X(type,
// name) for each; everything that walks the particles' arrays is generated from it: the
// members of Particles (host vectors) and of ParticleView (raw pointers, what both backends'
// loops index), resize, permute, the bytes per particle, the CUDA backend's device arrays,
// its upload, download and gather. Adding a field here adds it everywhere.
//
// C++17 and no CUDA types: the CUDA backend includes it as it is.
#include <cstddef>
#include <cstdint>

// clang-format off
#define HPCPLAN_SPH_PARTICLE_FIELDS(X)                                                       \
  X(double, x) X(double, y) X(double, z)         /* position */                              \
  X(double, vx) X(double, vy) X(double, vz)      /* velocity */                              \
  X(double, ax) X(double, ay) X(double, az)      /* acceleration of the current substep */   \
  X(double, rho)                                 /* density */                               \
  X(double, drho)                                /* density rate (continuity; water) */      \
  X(double, p)                                   /* pressure */                              \
  X(std::uint32_t, neighbours)                   /* within the support, itself excluded */   \
  X(std::uint32_t, id)                           /* index at creation; stable */             \
  X(std::uint8_t, wall)                          /* 0 fluid, else a wall (kNoSlipWall...) */
// clang-format on

namespace hpcplan::sph {

// The wall field's values: 0 is fluid; a wall particle is fixed and either obeys the preset's
// wall condition (no-slip for water) or is a free-slip symmetry plane.
inline constexpr std::uint8_t kNoSlipWall = 1, kFreeSlipWall = 2;

// One particle set's arrays as pointers: a trivially copyable value that a CUDA kernel takes
// by value and a CPU loop reads, so that the phases (physics/solvers.hpp) index both alike.
struct ParticleView {
#define HPCPLAN_SPH_POINTER_MEMBER(type, name) type* name = nullptr;
  HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_POINTER_MEMBER)
#undef HPCPLAN_SPH_POINTER_MEMBER
};

// fn(pointer_a, pointer_b) for each field of two views (same field, same type), in the list's
// order: copies, uploads, gathers.
template <class Fn>
void for_each_field_pair(const ParticleView& a, const ParticleView& b, Fn&& fn) {
#define HPCPLAN_SPH_PAIR_CALL(type, name) fn(a.name, b.name);
  HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_PAIR_CALL)
#undef HPCPLAN_SPH_PAIR_CALL
}

// fn(pointer) for each field of a view.
template <class Fn>
void for_each_field(ParticleView& a, Fn&& fn) {
#define HPCPLAN_SPH_FIELD_CALL(type, name) fn(a.name);
  HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_FIELD_CALL)
#undef HPCPLAN_SPH_FIELD_CALL
}

// Bytes held per particle, summed over the fields.
constexpr std::size_t kParticleFieldBytes = 0
#define HPCPLAN_SPH_FIELD_SIZE(type, name) +sizeof(type)
    HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_FIELD_SIZE)
#undef HPCPLAN_SPH_FIELD_SIZE
    ;

}  // namespace hpcplan::sph
