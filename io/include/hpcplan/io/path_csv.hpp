#pragma once
// A continuous-world path as CSV: a header (x,y or x,y,z), then one point per line with every
// digit a double carries, so a path read back is the path written.
#include <cstdio>
#include <string>
#include <vector>

#include "hpcplan/env/point.hpp"

namespace hpcplan {

template <int D>
std::string path_csv(const std::vector<env::Vec<D>>& path) {
  std::string s = D == 3 ? "x,y,z\n" : "x,y\n";
  char buf[64];
  for (const auto& q : path) {
    for (int k = 0; k < D; ++k) {
      std::snprintf(buf, sizeof buf, k ? ",%.17g" : "%.17g", q[k]);
      s += buf;
    }
    s += "\n";
  }
  return s;
}

}  // namespace hpcplan
