#include "hpcplan/sph/particles.hpp"

#include <algorithm>
#include <cstddef>
#include <utility>

namespace hpcplan::sph {

namespace {

// Which block holds a field of type T (the order of Particles::Blocks).
template <class T>
constexpr int kBlockOf = -1;
template <>
constexpr int kBlockOf<double> = 0;
template <>
constexpr int kBlockOf<std::uint32_t> = 1;
template <>
constexpr int kBlockOf<std::uint8_t> = 2;

enum Field : int {
#define HPCPLAN_SPH_FIELD_ENUM(type, name) field_##name,
  HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_FIELD_ENUM)
#undef HPCPLAN_SPH_FIELD_ENUM
      kFieldCount
};

constexpr int kFieldBlock[kFieldCount] = {
#define HPCPLAN_SPH_FIELD_BLOCK(type, name) kBlockOf<type>,
    HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_FIELD_BLOCK)
#undef HPCPLAN_SPH_FIELD_BLOCK
};
#define HPCPLAN_SPH_FIELD_HAS_BLOCK(type, name) \
  static_assert(kBlockOf<type> >= 0, "particle field " #name " has a type with no block");
HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_FIELD_HAS_BLOCK)
#undef HPCPLAN_SPH_FIELD_HAS_BLOCK

// A field's run within its block: the fields of one type before it.
constexpr std::size_t slot_of(int field) {
  std::size_t n = 0;
  for (int j = 0; j < field; ++j) n += kFieldBlock[j] == kFieldBlock[field];
  return n;
}
constexpr std::size_t fields_in_block(int block) {
  std::size_t n = 0;
  for (int j = 0; j < kFieldCount; ++j) n += kFieldBlock[j] == block;
  return n;
}
// The (n, 3) views of positions and velocities rely on x, y, z and vx, vy, vz being
// consecutive runs of one block.
static_assert(slot_of(field_y) == slot_of(field_x) + 1 && slot_of(field_z) == slot_of(field_x) + 2);
static_assert(slot_of(field_vy) == slot_of(field_vx) + 1 &&
              slot_of(field_vz) == slot_of(field_vx) + 2);

template <class T>
std::vector<T>& block(std::tuple<std::vector<double>, std::vector<std::uint32_t>,
                                 std::vector<std::uint8_t>>& blocks) {
  return std::get<std::vector<T>>(blocks);
}

}  // namespace

Particles::Particles(const Particles& other)
    : size_(other.size_), capacity_(other.capacity_), blocks_(other.blocks_) {
  bind();
}

Particles::Particles(Particles&& other) noexcept
    : size_(std::exchange(other.size_, 0)),
      capacity_(std::exchange(other.capacity_, 0)),
      blocks_(std::move(other.blocks_)),
      spare_(std::move(other.spare_)) {
  bind();
  other.blocks_ = {};
  other.spare_ = {};
  other.bind();
}

Particles& Particles::operator=(const Particles& other) {
  if (this == &other) return *this;
  blocks_ = other.blocks_;  // reuses this block's memory where it is large enough
  size_ = other.size_;
  capacity_ = other.capacity_;
  bind();
  return *this;
}

Particles& Particles::operator=(Particles&& other) noexcept {
  if (this == &other) return *this;
  blocks_ = std::move(other.blocks_);
  spare_ = std::move(other.spare_);
  size_ = std::exchange(other.size_, 0);
  capacity_ = std::exchange(other.capacity_, 0);
  bind();
  other.blocks_ = {};
  other.spare_ = {};
  other.bind();
  return *this;
}

void Particles::bind() {
#define HPCPLAN_SPH_BIND(type, name)                                                              \
  name.data_ =                                                                                    \
      capacity_ == 0 ? nullptr : block<type>(blocks_).data() + slot_of(field_##name) * capacity_; \
  name.size_ = size_;
  HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_BIND)
#undef HPCPLAN_SPH_BIND
}

void Particles::reallocate(std::size_t capacity) {
  Blocks grown;
  const std::size_t keep = std::min(size_, capacity);
#define HPCPLAN_SPH_REALLOCATE(type, name)                                       \
  {                                                                              \
    std::vector<type>& to = block<type>(grown);                                  \
    to.resize(fields_in_block(kBlockOf<type>) * capacity);                       \
    std::copy_n(name.data_, keep, to.data() + slot_of(field_##name) * capacity); \
  }
  HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_REALLOCATE)
#undef HPCPLAN_SPH_REALLOCATE
  blocks_ = std::move(grown);
  spare_ = {};
  capacity_ = capacity;
  size_ = keep;
  bind();
}

void Particles::resize(std::size_t n) {
  if (n > capacity_) {
    reallocate(std::max(n, 2 * capacity_));
  } else if (n > size_) {
#define HPCPLAN_SPH_ZERO(type, name) std::fill(name.data_ + size_, name.data_ + n, type{});
    HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_ZERO)
#undef HPCPLAN_SPH_ZERO
  }
  size_ = n;
  bind();
}

void Particles::shrink_to_fit() {
  if (capacity_ != size_) reallocate(size_);
}

void Particles::add(const Vec3& position, const Vec3& velocity, double rho0, bool is_wall) {
  const std::size_t i = size();
  resize(i + 1);
  x[i] = position[0], y[i] = position[1], z[i] = position[2];
  vx[i] = velocity[0], vy[i] = velocity[1], vz[i] = velocity[2];
  rho[i] = rho0;
  id[i] = static_cast<std::uint32_t>(i);
  wall[i] = is_wall ? kNoSlipWall : 0;
}

ParticleView Particles::view() {
  ParticleView v;
#define HPCPLAN_SPH_POINTER(type, name) v.name = name.data();
  HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_POINTER)
#undef HPCPLAN_SPH_POINTER
  return v;
}

void Particles::permute(std::span<const std::uint32_t> order) {
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(size_);
  // Entry k of each field's run in the spare block becomes old entry order[k]; then the two
  // blocks trade places (the old one is the next gather's target).
#define HPCPLAN_SPH_GATHER(type, name)                                                           \
  {                                                                                              \
    std::vector<type>& to = block<type>(spare_);                                                 \
    to.resize(block<type>(blocks_).size());                                                      \
    type* out = to.data() + slot_of(field_##name) * capacity_;                                   \
    const type* in = name.data_;                                                                 \
    _Pragma("omp parallel for schedule(static)") for (std::ptrdiff_t k = 0; k < n; ++k) out[k] = \
        in[order[k]];                                                                            \
  }
  HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_GATHER)
#undef HPCPLAN_SPH_GATHER
  std::swap(blocks_, spare_);
  bind();
}

}  // namespace hpcplan::sph
