#include "hpcplan/env/box_map_io.hpp"

#include <vector>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/text_lines.hpp"

namespace hpcplan::env {

BoxMap parse_box_map(std::string_view text, const std::string& name) {
  std::optional<Block> boundary;
  std::vector<Block> blocks;
  std::optional<Vec<3>> start, goal;
  for_each_directive(text, name, [&](int line, const std::vector<std::string_view>& w) {
    const std::string_view key = w[0];
    auto numbers = [&](std::size_t from) {
      std::vector<double> v;
      for (std::size_t i = from; i < w.size(); ++i) v.push_back(parse_number(w[i], name, line));
      return v;
    };
    if (key == "boundary" || key == "block") {
      if (w.size() != 7 && w.size() != 10)
        throw InputError(where(name, line) + std::string(key) +
                         " needs 6 coordinates and optionally r g b, got " +
                         std::to_string(w.size() - 1) + " values");
      const std::vector<double> v = numbers(1);
      Block b;
      b.line = line;
      for (int k = 0; k < 3; ++k) {
        b.box.lo[k] = v[k];
        b.box.hi[k] = v[k + 3];
        if (v[k] > v[k + 3])
          throw InputError(where(name, line) + std::string(key) + " has min > max on axis " +
                           "xyz"[k]);
      }
      if (v.size() == 9)
        for (int k = 0; k < 3; ++k) {
          // 0..1 or 0..255 colours are both common; anything else is a typo.
          if (v[6 + k] < 0 || v[6 + k] > 255)
            throw InputError(where(name, line) + "colour components must lie in 0..255");
          b.rgb[k] = v[6 + k];
        }
      if (key == "block") {
        blocks.push_back(b);
      } else {
        if (boundary) throw InputError(where(name, line) + "a second boundary line");
        for (int k = 0; k < 3; ++k)
          if (!(b.box.lo[k] < b.box.hi[k]))
            throw InputError(where(name, line) + "the boundary is empty along axis " + "xyz"[k]);
        boundary = b;
      }
    } else if (key == "start" || key == "goal") {
      if (w.size() != 4) throw InputError(where(name, line) + std::string(key) + " needs x y z");
      const std::vector<double> v = numbers(1);
      auto& slot = key == "start" ? start : goal;
      if (slot) throw InputError(where(name, line) + "a second " + std::string(key) + " line");
      slot = Vec<3>{v[0], v[1], v[2]};
    } else {
      throw InputError(where(name, line) + "unknown directive '" + std::string(key) +
                       "' (expected boundary, block, start or goal)");
    }
  });
  if (!boundary) throw InputError(name + ": no boundary line");
  // Colours given as 0..255 are stored as 0..1.
  auto normalise = [](std::array<double, 3>& c) {
    if (c[0] > 1 || c[1] > 1 || c[2] > 1)
      for (double& x : c) x /= 255.0;
  };
  for (Block& b : blocks) normalise(b.rgb);
  normalise(boundary->rgb);
  BoxMap map{BoxWorld(boundary->box, std::move(blocks)), start, goal};
  map.world.boundary_rgb = boundary->rgb;
  return map;
}

BoxMap load_box_map(const std::string& path) {
  return parse_box_map(read_text_file(path, "map file"), path);
}

}  // namespace hpcplan::env
