// parse_coordinates (grid_problem.hpp) in a source of its own: the option-values fuzz target
// (tests/fuzz/fuzz_option_values.cpp) compiles it without the rest of the grid problem.
#include <charconv>
#include <string>

#include "hpcplan/core/error.hpp"
#include "hpcplan/plan/grid_problem.hpp"

namespace hpcplan {

std::vector<int> parse_coordinates(std::string_view text, std::string_view what) {
  std::vector<int> coords;
  const auto fail = [&](const std::string& why) {
    throw InputError(std::string(what) + " '" + std::string(text) + "' is malformed: " + why);
  };
  if (text.empty()) fail("empty");
  std::size_t pos = 0;
  while (true) {
    const std::size_t comma = text.find(',', pos);
    const std::string_view item =
        text.substr(pos, comma == std::string_view::npos ? std::string_view::npos : comma - pos);
    int value = 0;
    const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), value);
    if (item.empty() || ec != std::errc() || end != item.data() + item.size())
      fail(std::string("'").append(item).append("' is not an integer"));
    coords.push_back(value);
    if (comma == std::string_view::npos) break;
    pos = comma + 1;
  }
  return coords;
}

}  // namespace hpcplan
