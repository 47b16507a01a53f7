#pragma once
// The box-map text format of seed 004, one directive per line:
//   boundary xmin ymin zmin xmax ymax zmax [r g b]   exactly once
//   block    xmin ymin zmin xmax ymax zmax [r g b]   any number
//   start x y z / goal x y z                          optional (hpcplan's addition: a map
//                                                     can carry its own query)
// '#' starts a comment; blank lines, tabs and CRLF line ends are accepted. Anything else is
// an InputError naming the file and line.
#include <optional>
#include <string>
#include <string_view>

#include "hpcplan/env/box_world.hpp"

namespace hpcplan::env {

struct BoxMap {
  BoxWorld world;
  std::optional<Vec<3>> start, goal;
};

BoxMap parse_box_map(std::string_view text, const std::string& name);
BoxMap load_box_map(const std::string& path);

}  // namespace hpcplan::env
