#pragma once
// How the lattice's sections are shared out among MPI ranks and their threads. A section is
// the set of tiles sharing their tile coordinates on the cut axis and every axis above it (a
// layer when the cut is the last axis; a row of a layer when it is the one before), so the
// tiles of consecutive sections are one run of tile indices. Contiguous slabs are balanced by
// free states, which the separable field gives exactly and cheaply: the free states of a
// section are those of the axes below the cut whose level sum stays below the threshold less
// the section's own levels, a convolution of per-axis histograms.
#include <cstdint>
#include <vector>

#include "hpcplan/dense/tile_layout.hpp"
#include "hpcplan/env/obstacle_source.hpp"

namespace hpcplan::dense {

// Free lattice states in each tile layer (exact up to double rounding).
std::vector<double> free_states_per_layer(const ObstacleSource& field, const TileLayout& layout);

// Free lattice states in each section of a cut at `cut_axis` (exact up to double rounding).
// Below the last axis the cut is on an axis of one cell per tile (cut_axis >= in-tile axes).
std::vector<double> free_states_per_section(const ObstacleSource& field, const TileLayout& layout,
                                            int cut_axis);

// parts + 1 bounds 0 = b_0 <= b_1 <= ... <= b_parts = weights.size(): part j holds layers
// [b_j, b_(j+1)), contiguous, with weights as equal as whole layers allow. Every part gets at
// least one layer while there are enough; the last parts are empty otherwise.
std::vector<int> balanced_slabs(const std::vector<double>& weights, int parts);

}  // namespace hpcplan::dense
