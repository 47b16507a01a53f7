#include "hpcplan/io/sph_report.hpp"

#include <algorithm>
#include <cstdio>

namespace hpcplan::io {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double particle_steps_per_s(const SphRun& r) {
  double ms = 0.0;
  for (double f : r.report.frame_ms) ms += f;
  return ms > 0.0 ? static_cast<double>(r.summary.fluid) * static_cast<double>(r.report.substeps) /
                        (ms * 1e-3)
                  : 0.0;
}

}  // namespace

nlohmann::json to_json(const SphRun& r) {
  const auto& rep = r.report;
  const double max_ms =
      rep.frame_ms.empty() ? 0.0 : *std::max_element(rep.frame_ms.begin(), rep.frame_ms.end());
  nlohmann::json j = {
      {"status", !rep.stable       ? "unstable"
                 : rep.interrupted ? "interrupted"
                                   : "ok"},
      {"preset", sph::to_string(r.options.preset)},
      {"scenario", sph::to_string(r.options.scenario)},
      {"particles", r.summary.fluid},
      {"wall_particles", r.wall_particles},
      {"frames", rep.frames},
      {"substeps", rep.substeps},
      {"restarted_at_frame", r.restarted_at_frame},
      {"box", {r.domain.lo, r.domain.hi}},
      {"ms_per_frame_median", median(rep.frame_ms)},
      {"ms_per_frame_max", max_ms},
      {"grid_ms_per_frame_median", median(rep.grid_ms)},
      {"particle_steps_per_s", particle_steps_per_s(r)},
      {"neighbours_mean", r.summary.neighbours_mean},
      {"neighbours_max", r.summary.neighbours_max},
      {"max_density_error", r.summary.max_density_error},
      {"kinetic_energy", r.summary.kinetic_energy},
      {"max_speed", r.summary.max_speed},
      {"mass", r.summary.mass},
      {"simulated_s", rep.frames * r.params.frame_dt},
      {"frame_dt", r.params.frame_dt},
      {"smoothing_length", r.params.smoothing_length},
      {"support", r.params.support},
      {"particle_mass", r.params.particle_mass},
      {"threads", r.threads},
      {"seed", r.options.seed},
      {"backend", r.backend},
  };
  if (!rep.stable) {
    j["unstable_frame"] = rep.unstable_frame;
    j["problem"] = rep.problem;
  }
  if (rep.interrupted) {
    j["interrupted_by"] = r.interrupted_by;
    j["checkpoint"] = r.checkpoint;
  }
  if (r.params.preset == sph::Preset::water) {
    j["particle_spacing"] = r.params.particle_spacing;
    j["sound_speed"] = r.params.sound_speed;
  }
  return j;
}

std::string to_summary(const SphRun& r) {
  const auto& rep = r.report;
  char buf[1024];
  std::string s;
  std::snprintf(buf, sizeof buf,
                "hpcplan sph: preset %s, scenario %s, %zu particles (+%zu wall), seed %llu, "
                "%d thread(s), backend %s\n",
                std::string(sph::to_string(r.options.preset)).c_str(),
                std::string(sph::to_string(r.options.scenario)).c_str(), r.summary.fluid,
                r.wall_particles, static_cast<unsigned long long>(r.options.seed), r.threads,
                r.backend.c_str());
  s += buf;
  std::snprintf(buf, sizeof buf, "  box            [%g, %g] x [%g, %g] x [%g, %g]\n",
                r.domain.lo[0], r.domain.hi[0], r.domain.lo[1], r.domain.hi[1], r.domain.lo[2],
                r.domain.hi[2]);
  s += buf;
  const double max_ms =
      rep.frame_ms.empty() ? 0.0 : *std::max_element(rep.frame_ms.begin(), rep.frame_ms.end());
  std::snprintf(
      buf, sizeof buf,
      "  status         %s\n  frames         %llu (%.3f s simulated), %llu substeps\n"
      "  ms per frame   median %.3f, max %.3f (grid %.3f)\n"
      "  throughput     %.3g particle-steps/s\n"
      "  neighbours     mean %.1f, max %u\n"
      "  density error  max %.4f\n  kinetic energy %.6g J, max speed %.3f m/s\n",
      !rep.stable
          ? ("unstable at frame " + std::to_string(rep.unstable_frame) + ": " + rep.problem).c_str()
      : rep.interrupted
          ? ("interrupted by " + r.interrupted_by + " after frame " + std::to_string(rep.frames) +
             (r.checkpoint.empty() ? std::string(" (no --checkpoint: nothing to restart from)")
                                   : "; continue with --restart " + r.checkpoint))
                .c_str()
          : "ok",
      static_cast<unsigned long long>(rep.frames), rep.frames * r.params.frame_dt,
      static_cast<unsigned long long>(rep.substeps), median(rep.frame_ms), max_ms,
      median(rep.grid_ms), particle_steps_per_s(r), r.summary.neighbours_mean,
      r.summary.neighbours_max, r.summary.max_density_error, r.summary.kinetic_energy,
      r.summary.max_speed);
  s += buf;
  return s;
}

std::string probes_csv(const sph::Probes& probes) {
  std::string s;
  for (std::size_t k = 0; k < probes.columns.size(); ++k) s += (k ? "," : "") + probes.columns[k];
  s += "\n";
  char buf[352];  // "%.6f" of any finite double fits
  for (const std::vector<double>& row : probes.rows) {
    for (std::size_t k = 0; k < row.size(); ++k) {
      std::snprintf(buf, sizeof buf, "%s%.6f", k ? "," : "", row[k]);
      s += buf;
    }
    s += "\n";
  }
  return s;
}

}  // namespace hpcplan::io
