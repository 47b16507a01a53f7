#pragma once
// The fluid's particles as a structure of arrays: one array per quantity, so that a phase
// streams through only the arrays it reads, and a particle's entries share one index. The
// arrays are the fields of particle_fields.hpp, declared from that one list.
// Boundary particles (the water preset's walls) live in the same arrays, flagged `wall`, so
// that one neighbour grid serves fluid-fluid and fluid-wall pairs.
//
// Storage: the fields of one type share one block, each field a run of capacity() entries in
// the list's order, so that x, y, z (and vx, vy, vz) are one strided 3 x capacity() array.
// A reader outside the engine (the Python module's NumPy views) can then see positions and
// velocities as (n, 3) arrays without a copy. permute() gathers into a second block kept for
// the purpose and swaps the two, so memory read through an earlier pointer stays allocated
// (holding a previous ordering) until the next resize beyond capacity().
//
// Threads: a value; phases write disjoint index ranges from several threads (each particle
// only its own entries), never resize concurrently.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <tuple>
#include <vector>

#include "hpcplan/sph/particle_fields.hpp"
#include "hpcplan/sph/vec3.hpp"

namespace hpcplan::sph {

// One field's entries inside its Particles' block: indexed, iterated and compared as the
// std::vector it stands for, but sized only by Particles::resize (every field at once).
template <class T>
class Column {
 public:
  using value_type = T;
  using size_type = std::size_t;
  using reference = T&;
  using const_reference = const T&;
  using iterator = T*;
  using const_iterator = const T*;

  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  T* data() { return data_; }
  const T* data() const { return data_; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  T* begin() { return data_; }
  T* end() { return data_ + size_; }
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size_; }
  T& back() { return data_[size_ - 1]; }
  const T& back() const { return data_[size_ - 1]; }
  std::span<T> span() { return {data_, size_}; }
  std::span<const T> span() const { return {data_, size_}; }
  std::vector<T> to_vector() const { return {begin(), end()}; }

  friend bool operator==(const Column& a, const Column& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end());
  }

 private:
  friend struct Particles;
  T* data_ = nullptr;
  std::size_t size_ = 0;
};

struct Particles {
#define HPCPLAN_SPH_COLUMN_MEMBER(type, name) Column<type> name;
  HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_COLUMN_MEMBER)
#undef HPCPLAN_SPH_COLUMN_MEMBER

  Particles() = default;
  Particles(const Particles& other);
  Particles(Particles&& other) noexcept;
  Particles& operator=(const Particles& other);
  Particles& operator=(Particles&& other) noexcept;

  std::size_t size() const {
    return size_;
  }
  // Entries a field's run holds: the distance, in entries, from one field to the next of its
  // type (x to y to z) in the block.
  std::size_t capacity() const {
    return capacity_;
  }
  // n particles; new entries are zero. Growing beyond capacity() reallocates (geometrically,
  // so that add() is amortised O(1)).
  void resize(std::size_t n);
  // Makes capacity() equal size() (the fluid's builders call it once the particles are made).
  void shrink_to_fit();
  // Appends a particle at rest with density rho0 (id = its index).
  void add(const Vec3& position, const Vec3& velocity, double rho0, bool is_wall);

  Vec3 position(std::size_t i) const {
    return {x[i], y[i], z[i]};
  }
  Vec3 velocity(std::size_t i) const {
    return {vx[i], vy[i], vz[i]};
  }

  // Every array as a pointer (valid until the next resize or permute).
  ParticleView view();

  // Reorders every array at once: entry k of each array becomes old entry order[k]. `order`
  // must be a permutation of 0 .. size()-1.
  void permute(std::span<const std::uint32_t> order);

  // Bytes held per particle, for memory budgets (each block is held twice once permute() has
  // run: the gather's target).
  static constexpr std::size_t kBytesPerParticle = kParticleFieldBytes;

 private:
  using Blocks =
      std::tuple<std::vector<double>, std::vector<std::uint32_t>, std::vector<std::uint8_t>>;
  void reallocate(std::size_t capacity);
  void bind();  // points every column at its run of the block

  std::size_t size_ = 0, capacity_ = 0;
  Blocks blocks_, spare_;
};

}  // namespace hpcplan::sph
