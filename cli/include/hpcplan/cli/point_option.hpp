#pragma once
// The continuous worlds' --start/--goal values ("x,y" or "x,y,z"): the parser hpcplan map3d and
// hpcplan sphere2d use, in a header of its own so that the option-values fuzz target
// (tests/fuzz/fuzz_option_values.cpp) runs the same code.
#include <cmath>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/point.hpp"

namespace hpcplan::cli {

// Exactly D comma-separated finite numbers: "x,y" (D = 2) or "x,y,z" (D = 3); InputError
// naming `option` otherwise.
template <int D>
env::Vec<D> parse_point(const std::string& text, const char* option) {
  std::vector<std::string> items;  // every comma-separated item, empty ones included
  for (std::size_t at = 0;;) {
    const std::size_t comma = text.find(',', at);
    items.push_back(text.substr(at, comma == std::string::npos ? comma : comma - at));
    if (comma == std::string::npos) break;
    at = comma + 1;
  }
  env::Vec<D> p{};
  for (std::size_t k = 0; k < items.size() && k < D; ++k) {
    // strtod, not stod: stod refused an underflow (5e-324, a subnormal, read as it is; 1e-400,
    // read as 0) as out of range, while the map files' parser reads both.
    const char* begin = items[k].c_str();
    char* end = nullptr;
    p[k] = std::strtod(begin, &end);
    if (end == begin || end != begin + items[k].size() || !std::isfinite(p[k]))
      throw InputError(std::string(option) + ": '" + items[k] + "' is not a finite number");
  }
  if (items.size() != D)
    throw InputError(std::string(option) + " needs " + std::to_string(D) +
                     " comma-separated coordinates, got '" + text + "'");
  return p;
}

}  // namespace hpcplan::cli
