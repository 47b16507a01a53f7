// A headless timer for the seed authors' CPU physics step (github.com/aneangel/particlePaths,
// MIT), used by bench/seed_peer.sh as a peer to `hpcplan sph --preset seed --scenario dynamic`.
// This file is ours; it only includes their particle.h and links their particle.cpp (built from
// a checkout outside this project, never copied into it).
//
// What one of their frames is: their CPU build calls updatePhysics(simState) once per 0.02 s
// frame (its timeStep), and updatePhysics itself moves the obstacles (updateObstacles), spawns
// (spawnParticles), builds the hash grid, computes density/pressure and forces, integrates,
// pushes particles out of walls and boxes and separates overlapping pairs. So a frame here is
// exactly one updatePhysics call; updateObstacles is NOT called again (their CUDA build calls it
// separately only because its GPU step does not).
//
// The set-up follows ours as closely as their API allows:
//   - their box scaling for N particles: side L = 5 (N / 1500)^(1/3), the hash grid as wide as
//     L / H + 2 cells (at least 35), which their main() sets from the particle count;
//   - their DYNAMIC_OBSTACLES scenario, built by their SimulationState::reset() (18 moving
//     boxes placed and sized relative to L); ours has 6 seeded boxes instead;
//   - all N particles active from the first frame, uniformly at random in the free part of the
//     box, each with their agitation kick (+-2.5 on the horizontal axes, 0..3 up; their y is up),
//     as our seed preset starts. Their own run instead streams 15 particles a frame from one
//     spout, which would take N / 15 frames before the N particles exist; particlesSpawned = N
//     turns their spawner into a no-op.
//
// Usage: seed_peer_driver N [WARMUP=10] [FRAMES=50] [SEED=1]
// Prints one JSON line: the median (and min, max) wall-clock ms of the FRAMES timed frames.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "particle.h"

namespace {

long arg_or(int argc, char** argv, int i, long fallback) {
  if (argc <= i) return fallback;
  char* end = nullptr;
  const long v = std::strtol(argv[i], &end, 10);
  if (end == argv[i] || *end != '\0' || v < 0) {
    std::fprintf(stderr, "seed_peer_driver: argument %d ('%s') is not a count\n", i, argv[i]);
    std::exit(2);
  }
  return v;
}

bool inside_any_box(const SimulationState& s, float x, float y, float z) {
  for (const Obstacle& o : s.obstacles)
    if (o.contains(x, y, z)) return true;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s N [WARMUP=10] [FRAMES=50] [SEED=1]\n", argv[0]);
    return 2;
  }
  const long n = arg_or(argc, argv, 1, 0);
  const long warmup = arg_or(argc, argv, 2, 10);
  const long frames = arg_or(argc, argv, 3, 50);
  const long seed = arg_or(argc, argv, 4, 1);
  if (n < 1 || frames < 1) {
    std::fprintf(stderr, "seed_peer_driver: N and FRAMES must be at least 1\n");
    return 2;
  }

  // Their scaling with the particle count (the globals are defined in their particle.cpp).
  boxsize = 5.0f * std::cbrt(static_cast<float>(n) / 1500.0f);
  gridWidth = std::max(35, static_cast<int>(boxsize / cellSize) + 2);

  // simState is their global; reset() reads boxsize to place the scenario's boxes.
  SimulationState& s = simState;
  s.currentScenario = Scenario::DYNAMIC_OBSTACLES;
  s.targgetParticleCount = static_cast<int>(n);
  s.reset();

  std::mt19937_64 rng(static_cast<std::uint64_t>(seed));
  // Inside the walls their step enforces (a particle's centre stays particleRad from a face).
  const float reach = boxsize / 2.0f - particleRad;
  std::uniform_real_distribution<float> pos(-reach, reach);
  std::uniform_real_distribution<float> side(-2.5f, 2.5f);
  std::uniform_real_distribution<float> up(0.0f, 3.0f);
  s.particles.reserve(static_cast<std::size_t>(n));
  while (static_cast<long>(s.particles.size()) < n) {
    const float x = pos(rng), y = pos(rng), z = pos(rng);
    if (inside_any_box(s, x, y, z)) continue;
    Particle p(x, y, z, side(rng), up(rng), side(rng));
    p.active = true;
    s.particles.push_back(p);
  }
  s.particlesSpawned = static_cast<int>(n);  // their spawner then has nothing left to place

  for (long f = 0; f < warmup; ++f) updatePhysics(s);

  std::vector<double> ms;
  ms.reserve(static_cast<std::size_t>(frames));
  for (long f = 0; f < frames; ++f) {
    const auto t0 = std::chrono::steady_clock::now();
    updatePhysics(s);
    const auto t1 = std::chrono::steady_clock::now();
    ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
  }
  std::vector<double> sorted = ms;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t m = sorted.size();
  const double median = m % 2 ? sorted[m / 2] : 0.5 * (sorted[m / 2 - 1] + sorted[m / 2]);

  // Untimed: the state the timed frames left, to compare with ours: the neighbours (within H)
  // that their findNeighbors returns, the kinetic energy with their particle mass, the particles
  // still active. Their findNeighbors misses about 40% of the pairs: for a cell whose int hash
  // is negative it takes `hash % grid.size()` in size_t, a bucket other than the one
  // buildSpatialGrid filled (it adds gridSize to the negative int remainder).
  buildSpatialGrid(s);
  std::vector<int> neighbours;
  double neighbour_sum = 0.0, kinetic = 0.0;
  long active = 0;
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    const Particle& p = s.particles[i];
    if (!p.active) continue;
    ++active;
    findNeighbors(s, i, neighbours);
    neighbour_sum += static_cast<double>(neighbours.size());
    kinetic += 0.5 * MASS * (double(p.vx) * p.vx + double(p.vy) * p.vy + double(p.vz) * p.vz);
  }

  std::printf(
      "{\"program\":\"particlePaths updatePhysics\",\"particles\":%ld,\"active\":%ld,"
      "\"box_side\":%.6g,\"grid_width\":%d,\"obstacles\":%zu,\"frame_dt\":%.6g,"
      "\"substeps\":%ld,\"warmup_frames\":%ld,\"frames\":%ld,\"ms_per_frame_median\":%.6g,"
      "\"ms_per_frame_min\":%.6g,\"ms_per_frame_max\":%.6g,\"neighbours_mean\":%.6g,"
      "\"kinetic_energy\":%.6g}\n",
      n, active, boxsize, gridWidth, s.obstacles.size(), timeStep, frames, warmup, frames, median,
      sorted.front(), sorted.back(), active ? neighbour_sum / active : 0.0, kinetic);
  return 0;
}
