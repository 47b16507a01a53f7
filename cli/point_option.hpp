#pragma once
// The continuous worlds' --start/--goal values ("x,y" or "x,y,z"): the parser hpcplan map3d and
// hpcplan sphere2d use, in a header of its own so that the option-values fuzz target
// (tests/fuzz/fuzz_option_values.cpp) runs the same code.
#include <cmath>
#include <exception>
#include <sstream>
#include <stdexcept>
#include <string>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/point.hpp"

namespace hpcplan::cli {

template <int D>
env::Vec<D> parse_point(const std::string& text, const char* option) {
  env::Vec<D> p{};
  std::stringstream in(text);
  std::string item;
  int k = 0;
  while (std::getline(in, item, ',')) {
    if (k == D) break;
    try {
      std::size_t used = 0;
      p[k] = std::stod(item, &used);
      if (used != item.size() || !std::isfinite(p[k])) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw InputError(std::string(option) + ": '" + item + "' is not a finite number");
    }
    ++k;
  }
  if (k != D || std::getline(in, item))
    throw InputError(std::string(option) + " needs " + std::to_string(D) +
                     " comma-separated coordinates, got '" + text + "'");
  return p;
}

}  // namespace hpcplan::cli
