#include "hpcplan/io/vtk_fluid.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string_view>

#include "hpcplan/core/atomic_file.hpp"

namespace hpcplan::io {

namespace {

// Appended raw data: each array is a UInt64 byte count followed by its bytes; a DataArray
// names its block by the block's offset from the start of the data.
class Appended {
 public:
  template <class T>
  std::uint64_t add(const std::vector<T>& values) {
    const std::uint64_t offset = data_.size();
    const std::uint64_t bytes = values.size() * sizeof(T);
    append(&bytes, sizeof bytes);
    append(values.data(), bytes);
    return offset;
  }
  const std::string& bytes() const { return data_; }

 private:
  void append(const void* p, std::size_t n) { data_.append(static_cast<const char*>(p), n); }
  std::string data_;
};

std::string data_array(const char* type, const char* name, int components, std::uint64_t offset) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "<DataArray type=\"%s\"%s%s%s NumberOfComponents=\"%d\" format=\"appended\" "
                "offset=\"%llu\"/>\n",
                type, name[0] ? " Name=\"" : "", name, name[0] ? "\"" : "", components,
                static_cast<unsigned long long>(offset));
  return buf;
}

std::string unstructured_grid(std::size_t points, std::size_t cells, const std::string& point_data,
                              const std::string& arrays, const Appended& data) {
  std::string s =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"" +
      std::to_string(points) + "\" NumberOfCells=\"" + std::to_string(cells) + "\">\n" +
      point_data + arrays + "</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_";
  s += data.bytes();
  s += "\n</AppendedData>\n</VTKFile>\n";
  return s;
}

std::string cells_xml(const Appended&, std::uint64_t conn, std::uint64_t offs,
                      std::uint64_t types) {
  return "<Cells>\n" + data_array("Int64", "connectivity", 1, conn) +
         data_array("Int64", "offsets", 1, offs) + data_array("UInt8", "types", 1, types) +
         "</Cells>\n";
}

// The points and cells, appended after the attribute arrays already in `data`, and the whole
// document around them.
std::string grid_document(Appended& data, const std::string& attributes,
                          const std::vector<double>& points,
                          const std::vector<std::int64_t>& connectivity,
                          const std::vector<std::int64_t>& offsets,
                          const std::vector<std::uint8_t>& types) {
  const std::uint64_t pts = data.add(points);
  const std::uint64_t conn = data.add(connectivity), offs = data.add(offsets),
                      typ = data.add(types);
  const std::string arrays = "<Points>\n" + data_array("Float64", "", 3, pts) + "</Points>\n" +
                             cells_xml(data, conn, offs, typ);
  return unstructured_grid(points.size() / 3, types.size(), attributes, arrays, data);
}

}  // namespace

std::string vtu_particles(const sph::FluidState& s) {
  const sph::Particles& p = s.particles;
  std::vector<double> points, velocity, density, pressure;
  std::vector<std::int64_t> connectivity, offsets, id;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.wall[i]) continue;
    const auto n = static_cast<std::int64_t>(density.size());
    points.insert(points.end(), {p.x[i], p.y[i], p.z[i]});
    velocity.insert(velocity.end(), {p.vx[i], p.vy[i], p.vz[i]});
    density.push_back(p.rho[i]);
    pressure.push_back(p.p[i]);
    id.push_back(p.id[i]);
    connectivity.push_back(n);
    offsets.push_back(n + 1);
  }
  const std::vector<std::uint8_t> types(density.size(), 1);  // VTK_VERTEX
  Appended data;
  const std::string point_data = "<PointData Scalars=\"density\" Vectors=\"velocity\">\n" +
                                 data_array("Float64", "velocity", 3, data.add(velocity)) +
                                 data_array("Float64", "density", 1, data.add(density)) +
                                 data_array("Float64", "pressure", 1, data.add(pressure)) +
                                 data_array("Int64", "id", 1, data.add(id)) + "</PointData>\n";
  return grid_document(data, point_data, points, connectivity, offsets, types);
}

std::string vtu_boxes(const std::vector<sph::MovingBox>& boxes) {
  std::vector<double> points;
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<double> speed;
  for (const sph::MovingBox& b : boxes) {
    const auto& lo = b.box.lo;
    const auto& hi = b.box.hi;
    // VTK_HEXAHEDRON's corner order: the bottom face counter-clockwise, then the top face.
    const double corners[8][3] = {
        {lo[0], lo[1], lo[2]}, {hi[0], lo[1], lo[2]}, {hi[0], hi[1], lo[2]}, {lo[0], hi[1], lo[2]},
        {lo[0], lo[1], hi[2]}, {hi[0], lo[1], hi[2]}, {hi[0], hi[1], hi[2]}, {lo[0], hi[1], hi[2]}};
    const auto first = static_cast<std::int64_t>(points.size() / 3);
    for (const auto& c : corners) points.insert(points.end(), {c[0], c[1], c[2]});
    for (int k = 0; k < 8; ++k) connectivity.push_back(first + k);
    offsets.push_back(first + 8);
    speed.push_back(sph::norm(b.velocity));
  }
  const std::vector<std::uint8_t> types(boxes.size(), 12);  // VTK_HEXAHEDRON
  Appended data;
  const std::string cell_data = "<CellData Scalars=\"speed\">\n" +
                                data_array("Float64", "speed", 1, data.add(speed)) +
                                "</CellData>\n";
  return grid_document(data, cell_data, points, connectivity, offsets, types);
}

std::string vtu_robot(const std::array<double, 3>& robot, const std::array<double, 3>& goal,
                      const std::vector<std::array<double, 3>>& plan,
                      const std::vector<std::array<double, 3>>& trail) {
  std::vector<double> points;
  std::vector<std::int64_t> connectivity, offsets, role;
  std::vector<std::uint8_t> types;
  auto add_cell = [&](const std::vector<std::array<double, 3>>& pts, std::uint8_t type, int r) {
    if (pts.empty()) return;
    for (const auto& q : pts) {
      connectivity.push_back(static_cast<std::int64_t>(points.size() / 3));
      points.insert(points.end(), {q[0], q[1], q[2]});
    }
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    types.push_back(type);
    role.push_back(r);
  };
  add_cell({robot}, 1, 0);  // VTK_VERTEX
  add_cell({goal}, 1, 1);
  if (plan.size() >= 2) add_cell(plan, 4, 2);  // VTK_POLY_LINE
  if (trail.size() >= 2) add_cell(trail, 4, 3);
  Appended data;
  const std::string cell_data = "<CellData Scalars=\"role\">\n" +
                                data_array("Int64", "role", 1, data.add(role)) + "</CellData>\n";
  return grid_document(data, cell_data, points, connectivity, offsets, types);
}

namespace {

std::string tag_of(std::uint64_t frame) {
  char tag[32];
  std::snprintf(tag, sizeof tag, "%06llu", static_cast<unsigned long long>(frame));
  return tag;
}

}  // namespace

std::optional<std::uint64_t> series_frame(std::string_view name) {
  // fluid_<at least 6 digits>.vtu (tag_of pads to 6; frames from 1,000,000 on have more).
  if (name.size() < 16 || !name.starts_with("fluid_") || !name.ends_with(".vtu")) return {};
  const std::string digits(name.substr(6, name.size() - 10));
  if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) return {};
  const std::uint64_t frame = std::stoull(digits);
  // Only the name the frame is written under: fluid_0000005.vtu is not frame 5's file (that is
  // fluid_000005.vtu), and counting both would list frame 5 twice.
  if (tag_of(frame) != digits) return {};
  return frame;
}

VtkSeries::VtkSeries(std::string dir) : dir_(std::move(dir)) {
  if (!dir_.empty() && dir_.back() != '/') dir_ += '/';
}

void VtkSeries::resume(std::uint64_t frame, double frame_dt) {
  namespace fs = std::filesystem;
  std::vector<std::uint64_t> frames;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir_, ec)) {
    const std::optional<std::uint64_t> f = series_frame(e.path().filename().string());
    if (f && *f <= frame) frames.push_back(*f);
  }
  std::sort(frames.begin(), frames.end());
  entries_.clear();
  for (const std::uint64_t f : frames) {
    const std::string tag = tag_of(f);
    entries_.push_back(
        {static_cast<double>(f) * frame_dt, tag, fs::exists(dir_ + "robot_" + tag + ".vtu", ec)});
  }
}

void VtkSeries::write(std::uint64_t frame, const sph::FluidState& state, const std::string& robot) {
  const std::string tag = tag_of(frame);
  write_file_atomically(dir_ + "fluid_" + tag + ".vtu", vtu_particles(state));
  write_file_atomically(dir_ + "boxes_" + tag + ".vtu", vtu_boxes(state.boxes));
  if (!robot.empty()) write_file_atomically(dir_ + "robot_" + tag + ".vtu", robot);
  entries_.push_back({state.time, tag, !robot.empty()});
  std::string pvd =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" "
      "byte_order=\"LittleEndian\">\n<Collection>\n";
  for (const Entry& e : entries_) {
    char line[384];
    std::snprintf(line, sizeof line,
                  "<DataSet timestep=\"%.9g\" part=\"0\" file=\"fluid_%s.vtu\"/>\n"
                  "<DataSet timestep=\"%.9g\" part=\"1\" file=\"boxes_%s.vtu\"/>\n",
                  e.time, e.tag.c_str(), e.time, e.tag.c_str());
    pvd += line;
    if (e.robot) {
      std::snprintf(line, sizeof line,
                    "<DataSet timestep=\"%.9g\" part=\"2\" file=\"robot_%s.vtu\"/>\n", e.time,
                    e.tag.c_str());
      pvd += line;
    }
  }
  pvd += "</Collection>\n</VTKFile>\n";
  write_file_atomically(dir_ + "fluid.pvd", pvd);
}

}  // namespace hpcplan::io
