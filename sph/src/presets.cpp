#include "hpcplan/sph/presets.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/sph/neighbour_lists.hpp"
#include "hpcplan/sph/step_backend.hpp"

namespace hpcplan::sph {

namespace {

constexpr double kG = 9.81;
constexpr int kWallLayers = 3;  // covers the support of 2.6 dx

// Uniform doubles in [0, 1) from SplitMix64 (53 bits).
class Uniform {
 public:
  explicit Uniform(std::uint64_t seed) : rng_(seed) {}
  double operator()() { return static_cast<double>(rng_.next() >> 11) * 0x1.0p-53; }
  double operator()(double lo, double hi) { return lo + (hi - lo) * (*this)(); }

 private:
  SplitMix64 rng_;
};

double seed_box_side(std::size_t n) {
  return 5.0 * std::cbrt(static_cast<double>(n) / 1500.0);
}

bool overlaps(const Box3& a, const Box3& b, double gap) {
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] + gap <= b.lo[k] || b.hi[k] + gap <= a.lo[k]) return false;
  return true;
}

std::vector<MovingBox> seed_boxes(const Box3& domain, Scenario scenario, Uniform& u) {
  std::vector<MovingBox> boxes;
  if (scenario == Scenario::particles) return boxes;
  const double l = domain.hi[0] - domain.lo[0];
  for (int tries = 0; boxes.size() < 6 && tries < 10000; ++tries) {
    MovingBox b;
    for (int k = 0; k < 3; ++k) {
      const double side = u(0.1, 0.2) * l;
      b.box.lo[k] = u(domain.lo[k], domain.hi[k] - side);
      b.box.hi[k] = b.box.lo[k] + side;
    }
    bool clear = true;
    for (const MovingBox& o : boxes) clear = clear && !overlaps(b.box, o.box, 0.05 * l);
    if (!clear) continue;
    if (scenario == Scenario::dynamic_boxes) {
      Vec3 d{u(-1, 1), u(-1, 1), u(-1, 1)};
      const double len = norm(d);
      if (len < 1e-3) continue;
      b.velocity = (u(0.5, 1.0) / len) * d;
    }
    boxes.push_back(b);
  }
  return boxes;
}

FluidState make_seed(const FluidOptions& o) {
  FluidState s;
  FluidParams& f = s.params;
  f.preset = Preset::seed;
  f.particle_mass = 0.05;
  f.rest_density = 1000.0;
  f.support = 0.15;
  f.smoothing_length = 0.15;
  f.gas_constant = 2000.0;
  f.viscosity = 0.1;
  f.gravity = {0.0, 0.0, -0.02};
  f.cfl = 0.25;
  f.restitution = 0.5;
  f.agitate_every = 250;
  const double l = seed_box_side(o.particles);
  s.domain = {{0, 0, 0}, {l, l, l}};
  Uniform u(o.seed);
  s.boxes = seed_boxes(s.domain, o.scenario, u);
  s.particles.resize(0);
  for (std::size_t i = 0; i < o.particles;) {
    const Vec3 x{u(0, l), u(0, l), u(0, l)};
    bool free = true;
    for (const MovingBox& b : s.boxes) free = free && !b.box.contains(x);
    if (!free) continue;
    s.particles.add(x,
                    {u(-f.kick_horizontal, f.kick_horizontal),
                     u(-f.kick_horizontal, f.kick_horizontal), u(0.0, f.kick_up)},
                    0.0, false);
    ++i;
  }
  s.fluid_count = o.particles;
  s.grid = NeighbourGrid(s.domain, f.support);
  return s;
}

struct WaterLayout {
  int nx = 0, ny = 0, nz = 0;
  double dx = 0.0;
  Box3 domain;                  // where the fluid may go
  Vec3 fluid_lo{}, fluid_hi{};  // the fluid block (on the lattice from the domain's corner)
  // A solid obstacle standing on the floor, in lattice cells [lo, hi) (none when lo == hi): its
  // cells are filled with wall particles.
  std::array<int, 3> solid_lo{}, solid_hi{};
};

// SPHERIC Test 2 (Kleefsman et al. 2005): every length snapped to the nearest lattice plane.
int cells(double length, double dx) {
  return static_cast<int>(std::lround(length / dx));
}

WaterLayout water_layout(const FluidOptions& o) {
  WaterLayout w;
  const double n = static_cast<double>(o.particles);
  if (o.scenario == Scenario::tank) {
    // nx = ny = 2 nz: a 1 m x 1 m tank, water 0.5 m deep.
    w.nz = std::max(2, static_cast<int>(std::lround(std::cbrt(n / 4.0))));
    w.nx = w.ny = 2 * w.nz;
    w.dx = 0.5 / w.nz;
    w.fluid_hi = {1.0, 1.0, 0.5};
    w.domain = {{0, 0, 0}, {1.0, 1.0, 0.75}};
  } else if (o.scenario == Scenario::column) {
    // nz = 2 nx = 2 ny, nx even so that the column's faces (x = 1.5 and 2.5) lie on the lattice.
    w.nx = std::max(2, static_cast<int>(std::lround(std::cbrt(n / 2.0))));
    w.nx += w.nx % 2;
    w.ny = w.nx;
    w.nz = 2 * w.nx;
    w.dx = 1.0 / w.nx;
    w.fluid_lo = {1.5, 0.0, 0.0};
    w.fluid_hi = {2.5, 1.0, 2.0};
    w.domain = {{0, 0, 0}, {4.0, 1.0, 3.0}};
  } else if (o.scenario == Scenario::marin) {
    // The water column is 1.228 x 1 x 0.55 m: nx ny nz = (1.228 / 0.55) (1 / 0.55) nz^3. The
    // height is exact (dx = 0.55 / nz); every other plane lies on the lattice nearest to it.
    const double shape = (kMarinColumn[0] / kMarinColumn[2]) * (kMarinColumn[1] / kMarinColumn[2]);
    w.nz = std::max(3, static_cast<int>(std::lround(std::cbrt(n / shape))));
    w.dx = kMarinColumn[2] / w.nz;
    const int cx = cells(kMarinTank[0], w.dx), cy = cells(kMarinTank[1], w.dx);
    const int front = cells(kMarinTank[0] - kMarinColumn[0], w.dx);
    w.nx = cx - front;
    w.ny = cy;
    w.fluid_lo = {front * w.dx, 0.0, 0.0};
    w.fluid_hi = {cx * w.dx, cy * w.dx, kMarinColumn[2]};
    w.domain = {{0, 0, 0}, {cx * w.dx, cy * w.dx, cells(kMarinTank[2], w.dx) * w.dx}};
    for (int k = 0; k < 3; ++k) {
      w.solid_lo[k] = cells(kMarinObstacle.lo[k], w.dx);
      w.solid_hi[k] = std::max(w.solid_lo[k] + 1, cells(kMarinObstacle.hi[k], w.dx));
    }
  } else {
    // nz = 2 nx, ny = nx / 4: the column a x a/4 x 2a.
    w.nx = std::max(4, static_cast<int>(std::lround(std::cbrt(2.0 * n))));
    w.nx += (4 - w.nx % 4) % 4;
    w.ny = w.nx / 4;
    w.nz = 2 * w.nx;
    const double a = kDamBreakColumn;
    w.dx = a / w.nx;
    w.fluid_hi = {a, a / 4.0, 2.0 * a};
    w.domain = {{0, 0, 0}, {6.0 * a, a / 4.0, 3.0 * a}};
  }
  return w;
}

FluidState make_water(const FluidOptions& o) {
  const WaterLayout w = water_layout(o);
  FluidState s;
  FluidParams& f = s.params;
  f.preset = Preset::water;
  f.rest_density = 1000.0;
  f.particle_spacing = w.dx;
  f.particle_mass = f.rest_density * w.dx * w.dx * w.dx;
  f.smoothing_length = 1.3 * w.dx;
  f.support = 2.0 * f.smoothing_length;
  f.gravity = {0.0, 0.0, -kG};
  const double height = w.fluid_hi[2] - w.fluid_lo[2];
  f.sound_speed = 10.0 * std::sqrt(2.0 * kG * height);
  f.alpha = 0.1;
  f.delta = 0.1;  // the literature's value (Molteni and Colagrossi 2009; Antuono et al. 2010)
  f.no_slip = true;
  f.kinematic_viscosity = 1.0e-6;  // water at 20 C
  f.list_skin = 0.15;              // Verlet lists (0.08 measured no faster: 1.48 M against 1.59 M
                                   // particle-steps/s, tank, 100k, 2 threads)
  f.cfl = 0.25;
  f.restitution = 0.0;
  s.domain = w.domain;
  const double b = f.rest_density * f.sound_speed * f.sound_speed / 7.0;
  auto hydrostatic = [&](double z) {
    return f.rest_density *
           std::pow(f.rest_density * kG * std::max(0.0, height - z) / b + 1.0, 1.0 / 7.0);
  };
  for (int k = 0; k < w.nz; ++k)
    for (int j = 0; j < w.ny; ++j)
      for (int i = 0; i < w.nx; ++i) {
        const Vec3 x{w.fluid_lo[0] + (i + 0.5) * w.dx, w.fluid_lo[1] + (j + 0.5) * w.dx,
                     w.fluid_lo[2] + (k + 0.5) * w.dx};
        s.particles.add(x, {0, 0, 0}, hydrostatic(x[2]), false);
      }
  s.fluid_count = s.particles.size();
  // Walls: the lattice continued kWallLayers deep below the floor and beyond the four sides,
  // up to the domain's top (which is open).
  const Vec3 size = s.domain.size();
  const int cx = static_cast<int>(std::lround(size[0] / w.dx));
  const int cy = static_cast<int>(std::lround(size[1] / w.dx));
  const int cz = static_cast<int>(std::lround(size[2] / w.dx));
  const auto in_solid = [&w](int i, int j, int k) {
    return i >= w.solid_lo[0] && i < w.solid_hi[0] && j >= w.solid_lo[1] && j < w.solid_hi[1] &&
           k >= w.solid_lo[2] && k < w.solid_hi[2];
  };
  for (int k = -kWallLayers; k < cz; ++k)
    for (int j = -kWallLayers; j < cy + kWallLayers; ++j)
      for (int i = -kWallLayers; i < cx + kWallLayers; ++i) {
        const bool inside = i >= 0 && i < cx && j >= 0 && j < cy && k >= 0;
        if (inside && !in_solid(i, j, k)) continue;
        s.particles.add({(i + 0.5) * w.dx, (j + 0.5) * w.dx, (k + 0.5) * w.dx}, {0, 0, 0},
                        f.rest_density, true);
        // The dam break is a slab a/4 wide standing in for Martin and Moyce's plane flow: its
        // two side walls are symmetry planes, free-slip (no friction the experiment had not).
        // Only the side walls proper: the floor and end-wall particles beyond the slab's width
        // are those walls' mirror images across the symmetry planes, so they stay no-slip.
        if (o.scenario == Scenario::dambreak && (j < 0 || j >= cy) && k >= 0 && i >= 0 && i < cx)
          s.particles.wall.back() = kFreeSlipWall;
      }
  const double pad = kWallLayers * w.dx;
  const Box3 region{{-pad, -pad, -pad}, {size[0] + pad, size[1] + pad, size[2]}};
  s.grid = NeighbourGrid(region, f.support);
  return s;
}

}  // namespace

Preset parse_preset(std::string_view name) {
  if (name == "seed") return Preset::seed;
  if (name == "water") return Preset::water;
  throw InputError("unknown --preset '" + std::string(name) + "' (expected seed or water)");
}

Scenario parse_scenario(std::string_view name) {
  if (name == "particles") return Scenario::particles;
  if (name == "static") return Scenario::static_boxes;
  if (name == "dynamic") return Scenario::dynamic_boxes;
  if (name == "dambreak") return Scenario::dambreak;
  if (name == "tank") return Scenario::tank;
  if (name == "column") return Scenario::column;
  if (name == "marin") return Scenario::marin;
  throw InputError("unknown --scenario '" + std::string(name) +
                   "' (expected particles, static, dynamic, dambreak, tank, column or marin)");
}

std::string_view to_string(Preset p) {
  return p == Preset::seed ? "seed" : "water";
}

std::string_view to_string(Scenario s) {
  switch (s) {
    case Scenario::particles:
      return "particles";
    case Scenario::static_boxes:
      return "static";
    case Scenario::dynamic_boxes:
      return "dynamic";
    case Scenario::dambreak:
      return "dambreak";
    case Scenario::tank:
      return "tank";
    case Scenario::column:
      return "column";
    case Scenario::marin:
      return "marin";
  }
  return "?";
}

void validate(const FluidOptions& o) {
  if (o.particles < 1) throw InputError("--particles must be at least 1");
  if (o.particles > 200'000'000) throw InputError("--particles must be at most 200000000");
  const bool water_scene = o.scenario == Scenario::dambreak || o.scenario == Scenario::tank ||
                           o.scenario == Scenario::column || o.scenario == Scenario::marin;
  if (o.preset == Preset::seed && water_scene)
    throw InputError("the seed preset has no walls to hold water: --scenario " +
                     std::string(to_string(o.scenario)) + " needs --preset water");
  // Six particles over the column's height (4.06 x 6^3 rounds to nz = 6 from 676): fewer make
  // the obstacle one particle thick, and the fluid on its two faces would interact through it.
  if (o.scenario == Scenario::marin && o.particles < 676)
    throw InputError(
        "--scenario marin needs --particles 676 or more (6 particles over the column's height; "
        "fewer leave the obstacle one particle thick)");
  if (o.preset == Preset::water && !water_scene)
    throw InputError(
        "the water preset runs --scenario tank, dambreak, column or marin (the seed's scenarios "
        "particles, static and dynamic are --preset seed)");
}

std::uint64_t estimated_bytes(const FluidOptions& o) {
  validate(o);
  double particles = static_cast<double>(o.particles), cells = 0.0;
  if (o.preset == Preset::seed) {
    cells = std::pow(std::ceil(seed_box_side(o.particles) / 0.15), 3);
  } else {
    const WaterLayout w = water_layout(o);
    const Vec3 size = w.domain.size();
    const double pad = 2 * kWallLayers;
    const double ex = size[0] / w.dx + pad, ey = size[1] / w.dx + pad, ez = size[2] / w.dx + pad;
    particles = ex * ey * ez;  // fluid and walls together never exceed the padded box
    cells = std::ceil(ex / 2.6) * std::ceil(ey / 2.6) * std::ceil(ez / 2.6);
  }
  // Particles twice over (the reordering's scratch copy), the grid (twice with Verlet lists:
  // the wider list grid), the Verlet lists' reference positions (24 B), the neighbour lists.
  const double verlet = o.preset == Preset::water ? 24.0 + 16.0 : 0.0;
  return static_cast<std::uint64_t>(
             particles * (2.0 * Particles::kBytesPerParticle + 16.0 + verlet) + 16.0 * cells) +
         NeighbourLists::bytes_for(static_cast<std::uint64_t>(particles), list_capacity(o.preset));
}

FluidState make_fluid(const FluidOptions& o) {
  validate(o);
  FluidState s = o.preset == Preset::seed ? make_seed(o) : make_water(o);
  s.seed = o.seed;
  s.particles.shrink_to_fit();  // built by add(): the blocks' spare growth given back
  return s;
}

}  // namespace hpcplan::sph
