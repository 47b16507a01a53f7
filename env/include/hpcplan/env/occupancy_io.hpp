#pragma once
// The occupancy files users bring, read into an OccupancyGrid:
//   .map    MovingAI / GPPC 2D maps: "type octile", "height H", "width W", "map", then H rows of
//           W characters. '.', 'G' and 'S' (swamp, passable from regular terrain) are ground;
//           '@', 'O' (out of bounds) and 'T' (trees) are blocked; 'W' (water) is traversable
//           only from water, so it is a class of its own: a grid of one class (ground or water)
//           has the other's cells blocked. Row y is the file's y-th row, x its column.
//   .3dmap  voxel maps (Brewer and Sturtevant 2018): "voxel W H D", then one "x y z" per
//           blocked voxel.
//   .npy    NumPy arrays of 1..16 dimensions, bool or uint8 (nonzero = blocked), C or Fortran
//           order; format versions 1.0, 2.0 and 3.0.
// Real files' quirks are accepted: CRLF line ends, trailing blank lines and spaces, header
// keywords in any case. Anything else is an InputError of one line naming the file (and the
// line): a wrong header, a short or long row, an unknown character, a voxel outside the box, a
// size the file cannot hold (a shape claiming more bytes than the file has is refused before
// anything is allocated).
//
// The movement model each format's published answers assume (env::MapFile::connectivity):
// .map 8-connected without corner cutting (the seed rule in 2D), .3dmap 26-connected without
// corner cutting (full connectivity in 3D); a .npy carries none (the user's choice).
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "hpcplan/env/occupancy_grid.hpp"

namespace hpcplan::env {

enum class MapFormat { movingai, voxel, npy };
enum class Terrain { ground, water };  // which class of a .map is free

// The format a path names by its extension (.map, .3dmap, .npy); InputError otherwise.
MapFormat map_format_of(const std::string& path);
std::string_view to_string(MapFormat f);
// "seed" for .map, "full" for .3dmap, "" for .npy: the connectivity the format's answers use.
std::string_view published_connectivity(MapFormat f);

OccupancyGrid parse_movingai_map(std::string_view text, const std::string& name,
                                 Terrain terrain = Terrain::ground);
// The largest grid a .3dmap may claim: 2 GiB of bits (2^34 voxels when W is a multiple of 64;
// rows along x are padded to 64 voxels, so "voxel 1 65535 65535" needs 32 GiB and is refused).
// The published voxel sets average 159 M (Warframe) to 478 M (Descent) voxels, per
// ShortestPathLab's tables. A header beyond it is refused before anything is allocated; callers
// may pass a lower limit (the fuzz target does, to keep each input cheap).
inline constexpr std::uint64_t kMaxVoxelGridBytes = std::uint64_t{2} << 30;
OccupancyGrid parse_voxel_map(std::string_view text, const std::string& name,
                              std::uint64_t max_grid_bytes = kMaxVoxelGridBytes);
// `bytes` is the whole file.
OccupancyGrid parse_npy(std::string_view bytes, const std::string& name);

// The character at (x, y) of a .map's rows, for a loader deciding the start's terrain:
// 'W' when the start stands in water. nullopt outside the map (or its row), and for text whose
// header is not a .map's.
std::optional<char> movingai_cell(std::string_view text, int x, int y);

// Reads a file of any of the three formats (by extension). `terrain` applies to .map only.
OccupancyGrid load_occupancy(const std::string& path, Terrain terrain = Terrain::ground);

// The header of a NumPy .npy file (format 1.0: magic, version, length, the dict padded with
// spaces to a multiple of 64 bytes and ending in '\n'; 2.0 only past 65535 bytes) for a
// C-order array of `shape` (NumPy order, first axis slowest) and dtype "<f4", "<i4" or "|u1"
// ("|b1" for bool); the data, row-major, follows it. What --field-out writes.
std::string npy_header(std::string_view dtype, std::span<const std::int64_t> shape);

// One problem of a scenario file.
struct ScenarioRow {
  int bucket = 0;
  std::string map;              // the map file the row names (as written)
  std::vector<int> map_size;    // .scen: width, height; .3dscen: none
  std::vector<int> start, goal; // x, y (,z)
  double optimal = 0.0;         // the published optimal length
  double ratio = 0.0;           // .3dscen's heuristic ratio (0 when absent)
};

struct Scenario {
  bool voxel = false;           // a .3dscen (3D, 26-connected) rather than a .scen
  std::string version;          // "1" for .scen, as written
  std::string map;              // the map the file names (.3dscen's header, or row 0's)
  std::vector<ScenarioRow> rows;
};

// .scen: "version 1" (or "version 1.0"), then tab-separated rows
//   bucket map width height start_x start_y goal_x goal_y optimal_length
// (whitespace-separated when a row has no tab; a map name with spaces needs the tabs). A file
// without a version line is the old format HOG2's ScenarioLoader reads as version 0: 7 columns,
// bucket map start_x start_y goal_x goal_y optimal_length (no map size; map_size stays empty).
// Coordinates must lie inside the row's width x height.
// .3dscen: "version 1", a line with the map's name, then whitespace-separated rows
//   start_x start_y start_z goal_x goal_y goal_z optimal_length heuristic_ratio
// (each row's bucket is its index / 10, as the voxel sets group them; coordinates 0..65534).
// Both: CRLF and blank lines accepted; a negative optimal length is an InputError.
Scenario parse_scenario(std::string_view text, const std::string& name, bool voxel);
Scenario load_scenario(const std::string& path);  // .3dscen by extension, .scen otherwise

}  // namespace hpcplan::env
