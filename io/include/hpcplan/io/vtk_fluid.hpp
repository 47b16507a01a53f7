#pragma once
// The fluid as VTK XML files that ParaView opens directly:
//   fluid_<frame>.vtu   the fluid particles as vertex cells, with point data velocity (3),
//                       density and pressure; Float64, little-endian, raw appended data;
//   boxes_<frame>.vtu   the obstacle boxes as hexahedra (an empty grid when there are none);
//   robot_<frame>.vtu   (hpcplan sim) the robot and the goal as vertices, the current plan and
//                       the robot's trail as polylines; cell data `role` (0 robot, 1 goal,
//                       2 plan, 3 trail);
//   fluid.pvd           the series: every written frame at its time, fluid as part 0,
//                       boxes as part 1 and, when written, the robot as part 2.
// Every file is written through a temporary file and a rename, the .pvd last, so a reader
// never sees a series naming a frame that is not complete.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hpcplan/sph/fluid_state.hpp"

namespace hpcplan::io {

std::string vtu_particles(const sph::FluidState& state);
std::string vtu_boxes(const std::vector<sph::MovingBox>& boxes);
std::string vtu_robot(const std::array<double, 3>& robot, const std::array<double, 3>& goal,
                      const std::vector<std::array<double, 3>>& plan,
                      const std::vector<std::array<double, 3>>& trail);

// The frame a series file's name holds ("fluid_000042.vtu" -> 42), or none for any other name:
// how VtkSeries::resume reads the directory (and what the fuzz target feeds names to).
std::optional<std::uint64_t> series_frame(std::string_view file_name);

class VtkSeries {
 public:
  // `dir` must exist (the CLI checks it before a run).
  explicit VtkSeries(std::string dir);
  // Writes frame `frame`'s files (with `robot`, a vtu_robot document, when not empty) and
  // rewrites the .pvd.
  void write(std::uint64_t frame, const sph::FluidState& state, const std::string& robot = {});
  std::size_t frames_written() const { return entries_.size(); }
  // A restarted run's series: the frames up to `frame` already in the directory (files
  // fluid_NNNNNN.vtu, with robot_NNNNNN.vtu where written), at time NNNNNN x frame_dt (a
  // frame ends at that exact multiple), so that the .pvd lists them as the uninterrupted run
  // would when the checkpoint's frame is one it wrote anyway (a multiple of --every): a run
  // that ended at another frame also wrote that last frame, and it stays listed.
  void resume(std::uint64_t frame, double frame_dt);

 private:
  std::string dir_;
  struct Entry {
    double time;
    std::string tag;
    bool robot;
  };
  std::vector<Entry> entries_;
};

}  // namespace hpcplan::io
