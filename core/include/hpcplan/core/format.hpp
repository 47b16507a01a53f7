#pragma once
#include <span>
#include <string>

namespace hpcplan {

// "3,4,5": the form --start/--goal accept, so messages can be pasted back as options.
inline std::string join_coordinates(std::span<const int> coords) {
  std::string out;
  for (std::size_t i = 0; i < coords.size(); ++i) {
    if (i) out.push_back(',');
    out.append(std::to_string(coords[i]));
  }
  return out;
}

}  // namespace hpcplan
