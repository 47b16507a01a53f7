#include "hpcplan/sim/safety.hpp"

#include <algorithm>
#include <cmath>

namespace hpcplan::sim {

double signed_distance_to_box(const sph::Box3& box, const env::Vec<3>& p) {
  double outside2 = 0.0, inside = std::numeric_limits<double>::infinity();
  bool is_inside = true;
  for (int k = 0; k < 3; ++k) {
    const double below = box.lo[k] - p[k], above = p[k] - box.hi[k];
    const double gap = std::max(below, above);  // > 0: outside along this axis
    if (gap > 0.0) {
      outside2 += gap * gap;
      is_inside = false;
    } else {
      inside = std::min(inside, -gap);  // distance to the nearer face of this axis
    }
  }
  return is_inside ? -inside : std::sqrt(outside2);
}

Clearance clearance(const sph::FluidState& state, const env::Vec<3>& robot,
                    const SafetyParams& params, std::span<const std::uint32_t> exclude) {
  Clearance c;
  const sph::Particles& p = state.particles;
  // The nearest centre by squared distance over every particle: ~25 us at 25,000 particles,
  // against 7 ms for the frame's physics, so no spatial index is worth keeping in step.
  double best2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double dx = p.x[i] - robot[0], dy = p.y[i] - robot[1], dz = p.z[i] - robot[2];
    const double d2 = dx * dx + dy * dy + dz * dz;
    if (d2 >= best2 || p.wall[i]) continue;
    if (std::find(exclude.begin(), exclude.end(), p.id[i]) != exclude.end()) continue;
    best2 = d2;
  }
  if (std::isfinite(best2))
    c.particles = std::sqrt(best2) - params.particle_radius - params.robot_radius;
  for (const sph::MovingBox& b : state.boxes)
    c.boxes = std::min(c.boxes, signed_distance_to_box(b.box, robot) - params.robot_radius);
  return c;
}

void SafetyRecord::observe(double c, double dt) {
  ++frames;
  min_clearance = std::min(min_clearance, c);
  const bool contact = c < 0.0;
  if (contact) {
    ++contact_frames;
    contact_time_s += dt;
    max_overlap = std::max(max_overlap, -c);
    if (!in_contact_) ++contacts;
  }
  in_contact_ = contact;
}

}  // namespace hpcplan::sim
