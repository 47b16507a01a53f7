#pragma once
// What a run reports about the fluid (fluid particles only; walls are scaffolding). Every sum
// runs in index order on one thread, so a report is as deterministic as the state.
#include <cstdint>
#include <string>
#include <vector>

#include "hpcplan/sph/fluid_state.hpp"
#include "hpcplan/sph/presets.hpp"

namespace hpcplan::sph {

struct FluidSummary {
  std::size_t fluid = 0;
  double mass = 0.0;
  Vec3 momentum{};
  double kinetic_energy = 0.0;
  double max_density_error = 0.0;  // max |rho - rho0| / rho0
  double neighbours_mean = 0.0;
  std::uint32_t neighbours_max = 0;
  double max_speed = 0.0;
};

FluidSummary summarise(const FluidState& state);

// The dam break's surge front in Martin and Moyce's variables: T = t sqrt(2 g / a) and
// Z = x_front / a (a = kDamBreakColumn, g from the state's gravity). x_front is the farthest x
// on the sampling line near the floor (mid-width, half a spacing up: the first particle layer)
// where the fluid's kernel-interpolated density sum_j m W(x - x_j) reaches half the rest
// density, as DualSPHysics' validations measure it: a detached drop or a film thinner than the
// kernel does not count as the front. The floor and the two side walls of the slab count as
// mirrors (each fluid particle's reflections join the sum), so the water's interior reads rho0
// on the line, not the half or less that a truncated kernel would sum. Samples every dx / 8,
// the crossing interpolated between two samples. `density_fraction`: the threshold as a
// fraction of the rest density.
struct SurgeFront {
  double t = 0.0, z = 0.0;
};
SurgeFront dam_break_front(const FluidState& state, double density_fraction = 0.5);

// The water's height at (x, y): the highest point of the vertical line there where the
// kernel-interpolated density reaches `density_fraction` of the rest density (the floor counts
// as a mirror), as a wave gauge or a volume-of-fluid code's 0.5 phase contour reads it: spray
// thinner than the kernel's width does not count, and a layer on the floor reads no less than
// about one spacing (with its mirror image it fills the kernel), so heights are resolved to
// about one spacing. 0 where the line is dry. Samples every dx / 8, the crossing interpolated
// between two samples.
double water_height(const FluidState& state, double x, double y, double density_fraction = 0.5);

// SPHERIC Test 2's four gauges (Kleefsman et al. 2005), on the tank's centre line.
struct Gauge {
  const char* name;
  double x;
};
inline constexpr Gauge kMarinGauges[] = {
    {"H1", 0.496}, {"H2", 0.992}, {"H3", 1.488}, {"H4", 2.638}};

// A scenario's measurements over a run, one vocabulary for all: the column names, then one row
// per reading. dambreak: T, Z (the surge front, every substep); marin: t and the four gauges'
// heights in metres (every `interval` seconds of simulated time); none for the others.
struct Probes {
  Scenario scenario = Scenario::particles;
  std::vector<std::string> columns;
  double interval = 0.0;  // seconds between readings; 0: every substep
  std::vector<std::vector<double>> rows;
};
Probes probes_for(Scenario scenario);
// Takes a reading if one is due at the state's time (the first substep at or after each
// multiple of the interval, counted from the rows already taken: a restart continues them).
void record_probes(const FluidState& state, Probes& probes);

}  // namespace hpcplan::sph
