#pragma once
// A fluid run's checkpoint: everything the next frames depend on, so that a run restarted from
// it continues bit for bit as the uninterrupted run would (tests/sph/test_sph_cli.sh).
//
// What is saved, and why it suffices:
//   - the problem (preset, scenario, particles asked for, seed): the parameters, domain,
//     neighbour grid and wall particles are rebuilt from it by make_fluid, exactly as at the
//     start, and the saved particle counts must match what it builds;
//   - the frames completed, the simulated time and the substep count (the reordering by cell
//     runs every few substeps, counted from the start; the agitation depends on the frame);
//   - every particle field of particle_fields.hpp in the current particle order (the order of
//     the sums, so the order of round-off), and every box's position and velocity;
//   - the scenario's probe rows so far (the dam break's front, the MARIN gauges), so that
//     --front-csv and --gauges-csv cover the whole run.
// Nothing else carries over a frame boundary: the CPU backend rebuilds its grid and neighbour
// lists at every frame's first substep (its Verlet lists live within a frame), the CUDA
// backend sorts by cell every substep.
// Checked on reading: the parameters the state was computed with (as numbers) equal those its
// problem builds now, the time is its frame's end, the ids are a permutation and the walls are
// the built ones, and the file is large enough for the particles it claims.
//
// The file: core's checkpoint envelope (core/checkpoint_file.hpp: kind, format, version,
// checksum) around the payload above. A file that is not a fluid checkpoint, is cut short,
// fails its checksum, comes from another version or describes another problem is an InputError
// naming the file and what is wrong.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "hpcplan/sph/fluid_state.hpp"
#include "hpcplan/sph/presets.hpp"

namespace hpcplan::sph {

struct FluidCheckpoint {
  FluidOptions options;
  std::uint64_t frame = 0;  // frames completed
  FluidState state;         // as make_fluid(options) builds it, then the saved dynamics
  std::vector<std::vector<double>> probe_rows;  // the scenario's Probes::rows so far
};

// The checkpoint's bytes; `state` must have every array current (Fluid::full_state()).
std::string encode_checkpoint(const FluidOptions& options, std::uint64_t frame,
                              const FluidState& state,
                              const std::vector<std::vector<double>>& probe_rows);

// The checkpoint in `bytes`, read from `name` (for messages). InputError when damaged,
// foreign, of another version or of a problem make_fluid does not rebuild to the same counts.
FluidCheckpoint decode_checkpoint(std::string_view bytes, const std::string& name);
// What decode_checkpoint reads inside the envelope (its payload, after the envelope's checks
// and checksum): the fuzz target (tests/fuzz) feeds it directly, since a mutated file almost
// never passes the checksum. The same checks, the same InputErrors.
FluidCheckpoint decode_checkpoint_payload(std::string_view payload, const std::string& name);

// Reads and decodes a file: InputError if it cannot be read, as decode_checkpoint otherwise.
FluidCheckpoint read_checkpoint(const std::string& path);

}  // namespace hpcplan::sph
