#pragma once
// The fluid as VTK XML files that ParaView opens directly:
//   fluid_<frame>.vtu   the fluid particles as vertex cells, with point data velocity (3),
//                       density and pressure; Float64, little-endian, raw appended data;
//   boxes_<frame>.vtu   the obstacle boxes as hexahedra (an empty grid when there are none);
//   fluid.pvd           the series: every written frame at its time, fluid as part 0 and
//                       boxes as part 1.
// Every file is written through a temporary file and a rename, the .pvd last, so a reader
// never sees a series naming a frame that is not complete.
#include <cstdint>
#include <string>
#include <vector>

#include "hpcplan/sph/fluid_state.hpp"

namespace hpcplan::io {

std::string vtu_particles(const sph::FluidState& state);
std::string vtu_boxes(const std::vector<sph::MovingBox>& boxes);

class VtkSeries {
 public:
  // `dir` must exist (the CLI checks it before a run).
  explicit VtkSeries(std::string dir);
  // Writes frame `frame`'s two files and rewrites the .pvd.
  void write(std::uint64_t frame, const sph::FluidState& state);
  std::size_t frames_written() const { return entries_.size(); }

 private:
  std::string dir_;
  std::vector<std::pair<double, std::string>> entries_;  // time, frame tag
};

}  // namespace hpcplan::io
