#include "hpcplan/dense/slab_plan.hpp"

#include <algorithm>
#include <stdexcept>

namespace hpcplan::dense {

namespace {

// An occupancy grid's free cells per lattice layer of its last axis: each layer is one run of
// its bits.
std::vector<double> occupancy_free_per_layer(const OccupancyGrid& grid, const TileLayout& layout) {
  const int last = grid.dims() - 1;
  std::vector<double> layers(layout.layers(), 0.0);
  const int side = layout.side(last);
  if (grid.dims() == 1) {
    for (int z = 0; z < grid.size(0); ++z)
      if (grid.free_at(static_cast<std::uint64_t>(z))) layers[z / side] += 1.0;
    return layers;
  }
  const auto layer_bits = static_cast<std::uint64_t>(grid.stride(last));
  for (int z = 0; z < grid.size(last); ++z) {
    const std::uint64_t begin = static_cast<std::uint64_t>(z) * layer_bits;
    layers[z / side] += static_cast<double>(grid.count_free(begin, begin + layer_bits));
  }
  return layers;
}

// below[k]: the cells of the first `axes` axes whose level sum is under k, for k = 0 to the
// largest sum + 1 (a convolution of the axes' level histograms, then a running sum).
std::vector<double> cells_below_level_sum(const GogField& field, int axes) {
  std::vector<double> sums(1, 1.0);
  for (int a = 0; a < axes; ++a) {
    double hist[4] = {0, 0, 0, 0};
    const std::uint8_t* table = field.level_table(a);
    for (int x = 0; x < field.extent(); ++x) hist[table[x]] += 1.0;
    std::vector<double> next(sums.size() + 3, 0.0);
    for (std::size_t i = 0; i < sums.size(); ++i)
      for (int l = 0; l < 4; ++l) next[i + l] += sums[i] * hist[l];
    sums.swap(next);
  }
  std::vector<double> below(sums.size() + 1, 0.0);
  for (std::size_t i = 0; i < sums.size(); ++i) below[i + 1] = below[i] + sums[i];
  return below;
}

// The tile coordinates of section `s` on the axes from `cut` up (one cell per tile there).
void section_coords(const TileLayout& layout, int cut, std::uint64_t s, int* c) {
  for (int a = cut; a < layout.dims(); ++a) {
    c[a] = static_cast<int>(s % static_cast<std::uint64_t>(layout.tiles(a)));
    s /= static_cast<std::uint64_t>(layout.tiles(a));
  }
}

std::uint64_t section_count(const TileLayout& layout, int cut) {
  std::uint64_t n = 1;
  for (int a = cut; a < layout.dims(); ++a) n *= static_cast<std::uint64_t>(layout.tiles(a));
  return n;
}

}  // namespace

std::vector<double> free_states_per_section(const ObstacleSource& source, const TileLayout& layout,
                                            int cut) {
  const int dims = layout.dims();
  if (cut == dims - 1) return free_states_per_layer(source, layout);
  if (cut < layout.in_tile_axes() || cut >= dims)
    throw std::logic_error("free_states_per_section: a cut inside a tile");
  std::vector<double> sections(section_count(layout, cut), 0.0);
  int c[kMaxDims] = {};
  if (source.is_occupancy()) {
    // A section inside the grid's shape is one run of stride(cut) bits.
    const OccupancyGrid& grid = source.occupancy();
    const auto run = static_cast<std::uint64_t>(grid.stride(cut));
    for (std::uint64_t s = 0; s < sections.size(); ++s) {
      section_coords(layout, cut, s, c);
      std::uint64_t begin = 0;
      bool inside = true;
      for (int a = cut; a < dims; ++a) {
        inside = inside && c[a] < grid.size(a);
        begin += static_cast<std::uint64_t>(c[a]) * static_cast<std::uint64_t>(grid.stride(a));
      }
      if (inside) sections[s] = static_cast<double>(grid.count_free(begin, begin + run));
    }
    return sections;
  }
  const GogField& field = source.gog();
  const std::vector<double> below = cells_below_level_sum(field, cut);
  for (std::uint64_t s = 0; s < sections.size(); ++s) {
    section_coords(layout, cut, s, c);
    int room = field.threshold();
    for (int a = cut; a < dims; ++a) room -= field.level_table(a)[c[a]];
    sections[s] = room <= 0 ? 0.0 : below[std::min<std::size_t>(room, below.size() - 1)];
  }
  return sections;
}

std::vector<double> free_states_per_layer(const ObstacleSource& source, const TileLayout& layout) {
  if (source.is_occupancy()) return occupancy_free_per_layer(source.occupancy(), layout);
  const GogField& field = source.gog();
  const int dims = field.dims(), extent = field.extent(), last = dims - 1;
  const std::vector<double> below = cells_below_level_sum(field, last);
  const std::uint8_t* table = field.level_table(last);
  std::vector<double> layers(layout.layers(), 0.0);
  const int side = layout.side(last);
  for (int z = 0; z < extent; ++z) {
    const int room = field.threshold() - table[z];
    const double free = room <= 0 ? 0.0 : below[std::min<std::size_t>(room, below.size() - 1)];
    layers[z / side] += free;
  }
  return layers;
}

std::vector<int> balanced_slabs(const std::vector<double>& weights, int parts) {
  if (parts < 1) throw std::logic_error("balanced_slabs: no parts");
  const int n = static_cast<int>(weights.size());
  std::vector<int> bounds(parts + 1, n);
  bounds[0] = 0;
  double total = 0.0;
  for (double w : weights) total += w;
  double running = 0.0;
  int layer = 0;
  for (int j = 1; j < parts; ++j) {
    const double share = total * j / parts;
    // Take layers while the running total stays nearer the share with the layer than without.
    while (layer < n && running + weights[layer] / 2 < share) running += weights[layer++];
    // At least one layer per part while layers remain for the parts after it.
    const int lo = bounds[j - 1] + 1, hi = n - (parts - j);
    int b = std::clamp(layer, std::min(lo, n), std::max(std::min(lo, n), hi));
    for (; layer < b; ++layer) running += weights[layer];
    for (; layer > b;) running -= weights[--layer];
    bounds[j] = b;
  }
  return bounds;
}

}  // namespace hpcplan::dense
