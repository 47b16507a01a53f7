#include "hpcplan/sph/checkpoint.hpp"

#include <cmath>

#include "hpcplan/core/checkpoint_file.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/sph/diagnostics.hpp"
#include "hpcplan/sph/particle_fields.hpp"

namespace hpcplan::sph {

using checkpoint::Reader;
using checkpoint::Writer;

namespace {

constexpr std::string_view kMagic = "hpcplan fluid checkpoint\n";
// 2: the water preset's delta-SPH, no-slip walls and wall kinds (a format-1 file holds a
// fluid of the earlier physics).
constexpr std::uint32_t kFormat = 3;  // 3: probe rows of any width (2: the front's pairs)

// The parameters a checkpoint's state was computed with, as numbers: a restart whose rebuilt
// parameters differ (another physics, another build's presets) is refused.
std::vector<double> fingerprint(const FluidParams& f) {
  return {static_cast<double>(f.preset),
          f.particle_mass,
          f.rest_density,
          f.support,
          f.smoothing_length,
          f.gravity[0],
          f.gravity[1],
          f.gravity[2],
          f.gas_constant,
          f.viscosity,
          f.sound_speed,
          f.alpha,
          f.delta,
          f.no_slip ? 1.0 : 0.0,
          f.kinematic_viscosity,
          f.particle_spacing,
          f.frame_dt,
          f.cfl,
          f.restitution,
          static_cast<double>(f.reorder_every),
          f.list_skin,
          static_cast<double>(f.agitate_every),
          f.kick_horizontal,
          f.kick_up};
}

}  // namespace

std::string encode_checkpoint(const FluidOptions& o, std::uint64_t frame, const FluidState& s,
                              const std::vector<std::vector<double>>& probe_rows) {
  Writer w;
  w.put(static_cast<std::uint8_t>(o.preset));
  w.put(static_cast<std::uint8_t>(o.scenario));
  w.put<std::uint64_t>(o.particles);
  w.put(o.seed);
  w.put(frame);
  w.put_array(fingerprint(s.params));
  w.put(s.time);
  w.put(s.substeps);
  w.put<std::uint64_t>(s.fluid_count);
  w.put<std::uint64_t>(s.boxes.size());
  for (const MovingBox& b : s.boxes) w.put(b);
  const std::uint64_t n = s.particles.size();
  w.put(n);
#define HPCPLAN_SPH_SAVE_FIELD(type, name) w.put_array(s.particles.name.span());
  HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_SAVE_FIELD)
#undef HPCPLAN_SPH_SAVE_FIELD
  w.put<std::uint64_t>(probe_rows.size());
  w.put<std::uint64_t>(probe_rows.empty() ? 0 : probe_rows.front().size());
  for (const std::vector<double>& row : probe_rows)
    for (const double v : row) w.put(v);
  return checkpoint::seal(kMagic, kFormat, w.bytes());
}

FluidCheckpoint decode_checkpoint(std::string_view bytes, const std::string& name) {
  return decode_checkpoint_payload(
      checkpoint::open(bytes, kMagic, kFormat, "an hpcplan fluid checkpoint", name), name);
}

FluidCheckpoint decode_checkpoint_payload(std::string_view payload, const std::string& name) {
  Reader p(payload, name);
  FluidCheckpoint c;
  const auto preset = p.get<std::uint8_t>();
  const auto scenario = p.get<std::uint8_t>();
  if (preset > static_cast<std::uint8_t>(Preset::water) ||
      scenario > static_cast<std::uint8_t>(Scenario::marin))
    p.fail("names an unknown preset or scenario");
  c.options.preset = static_cast<Preset>(preset);
  c.options.scenario = static_cast<Scenario>(scenario);
  c.options.particles = p.get<std::uint64_t>();
  c.options.seed = p.get<std::uint64_t>();
  try {
    validate(c.options);
  } catch (const InputError& e) {
    p.fail(std::string("describes a run hpcplan refuses: ") + e.what());
  }
  c.frame = p.get<std::uint64_t>();
  // The file must hold at least the fields of the particles it claims (half of them: the water
  // lattice rounds), before the fluid is built: a small file cannot make it allocate much.
  if (static_cast<double>(c.options.particles) * 0.5 * kParticleFieldBytes >
      static_cast<double>(payload.size()))
    p.fail("claims " + std::to_string(c.options.particles) +
           " particles but is too small to hold them (damaged)");
  c.state = make_fluid(c.options);  // parameters, domain, grid, walls: as at the start
  FluidState& s = c.state;
  std::vector<double> saved_params;
  const std::vector<double> built_params = fingerprint(s.params);
  p.get_array(saved_params, built_params.size());
  for (std::size_t k = 0; k < built_params.size(); ++k)
    if (!(saved_params[k] == built_params[k]))
      p.fail("was computed with other fluid parameters (another build's physics or presets)");
  // The walls as they are built (by id), to check the saved ones against: the flags and
  // positions only, not a copy of the whole state.
  const std::vector<std::uint8_t> built_wall = s.particles.wall.to_vector();
  const std::vector<double> built_x = s.particles.x.to_vector(),
                            built_y = s.particles.y.to_vector(),
                            built_z = s.particles.z.to_vector();
  s.time = p.get<double>();
  s.substeps = p.get<std::uint64_t>();
  const auto fluid = p.get<std::uint64_t>();
  const auto boxes = p.get<std::uint64_t>();
  if (fluid != s.fluid_count || boxes != s.boxes.size())
    p.fail("does not match the fluid its options build (" + std::to_string(fluid) +
           " fluid particles and " + std::to_string(boxes) + " boxes saved, " +
           std::to_string(s.fluid_count) + " and " + std::to_string(s.boxes.size()) + " built)");
  for (MovingBox& b : s.boxes) b = p.get<MovingBox>();
  const auto n = p.get<std::uint64_t>();
  if (n != s.particles.size())
    p.fail("holds " + std::to_string(n) + " particles; its options build " +
           std::to_string(s.particles.size()));
#define HPCPLAN_SPH_LOAD_FIELD(type, name) p.get_array(s.particles.name.span());
  HPCPLAN_SPH_PARTICLE_FIELDS(HPCPLAN_SPH_LOAD_FIELD)
#undef HPCPLAN_SPH_LOAD_FIELD
  // A frame ends at a multiple of frame_dt (Fluid::advance_frame).
  const double end = static_cast<double>(c.frame) * s.params.frame_dt;
  if (c.frame > 100'000'000 || !(std::abs(s.time - end) <= 1e-9 * (1.0 + end)))
    p.fail("holds a time that is not its frame's end (damaged)");
  // The probe rows: as many as the run has read (the dam break every substep and at the start;
  // the gauges every interval of simulated time), each of the scenario's width, all finite.
  const auto rows = p.get<std::uint64_t>();
  const auto columns = p.get<std::uint64_t>();
  const Probes kind = probes_for(c.options.scenario);
  const std::uint64_t width = kind.columns.size();
  std::uint64_t expected = 0;
  if (kind.scenario == Scenario::dambreak) expected = s.substeps + 1;
  if (kind.scenario == Scenario::marin)
    expected = static_cast<std::uint64_t>(std::floor(s.time / kind.interval + 1e-9)) + 1;
  if ((width == 0 && rows > 0) || columns != (rows > 0 ? width : 0) || rows + 1 < expected ||
      rows > expected + 1 || (rows > 0 && rows > p.left() / 8 / columns))
    p.fail("holds probe rows that do not fit its scenario and time (damaged)");
  c.probe_rows.assign(rows, std::vector<double>(columns));
  for (std::vector<double>& row : c.probe_rows)
    for (double& v : row)
      if (v = p.get<double>(); !std::isfinite(v))
        p.fail("holds a probe reading that is not finite (damaged)");
  if (p.left() != 0) p.fail("has bytes after its end (damaged)");
  for (const MovingBox& b : s.boxes)
    for (int k = 0; k < 3; ++k)
      if (!(b.box.lo[k] >= s.domain.lo[k] && b.box.hi[k] <= s.domain.hi[k] &&
            b.box.lo[k] <= b.box.hi[k] && std::isfinite(b.velocity[k])))
        p.fail("holds a box outside the domain (damaged)");
  // The ids are a permutation, and each wall particle is the one built (walls never move).
  std::vector<std::uint8_t> seen(n, 0);
  for (std::uint64_t k = 0; k < n; ++k) {
    const std::uint32_t id = s.particles.id[k];
    if (id >= n || seen[id]) p.fail("holds particle ids that are not a permutation (damaged)");
    seen[id] = 1;
    if (s.particles.wall[k] != built_wall[id] ||
        (built_wall[id] && (s.particles.x[k] != built_x[id] || s.particles.y[k] != built_y[id] ||
                            s.particles.z[k] != built_z[id])))
      p.fail("holds walls other than its problem's (another build's walls, or damaged)");
  }
  return c;
}

FluidCheckpoint read_checkpoint(const std::string& path) {
  return decode_checkpoint(
      checkpoint::read_regular_file(path, kMagic, "an hpcplan fluid checkpoint"), path);
}

}  // namespace hpcplan::sph
