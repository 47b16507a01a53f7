#pragma once
#include <cstdint>
#include <cstdio>
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

// "3.25 GB": bytes in decimal units with three significant digits, for messages.
inline std::string format_bytes(std::uint64_t bytes) {
  static const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  double v = static_cast<double>(bytes);
  int u = 0;
  while (v >= 1000.0 && u < 6) {
    v /= 1000.0;
    ++u;
  }
  char text[32];
  std::snprintf(text, sizeof text, u == 0 ? "%.0f %s" : "%.3g %s", v, units[u]);
  return text;
}

}  // namespace hpcplan
