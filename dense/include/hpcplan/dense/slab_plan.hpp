#pragma once
// How the lattice's layers (along the last axis) are shared out: among MPI ranks, one slab
// each, and within a rank among its threads. Slabs are contiguous, so a move crosses at most
// into the next slab, and are balanced by free states, which the separable field gives exactly
// and cheaply: the free states of a layer at last coordinate z are those of the first d - 1
// axes whose level sum stays below threshold - level(z), a convolution of per-axis histograms.
#include <cstdint>
#include <vector>

#include "hpcplan/dense/tile_layout.hpp"
#include "hpcplan/env/obstacle_source.hpp"

namespace hpcplan::dense {

// Free lattice states in each tile layer (exact up to double rounding).
std::vector<double> free_states_per_layer(const ObstacleSource& field, const TileLayout& layout);

// parts + 1 bounds 0 = b_0 <= b_1 <= ... <= b_parts = weights.size(): part j holds layers
// [b_j, b_(j+1)), contiguous, with weights as equal as whole layers allow. Every part gets at
// least one layer while there are enough; the last parts are empty otherwise.
std::vector<int> balanced_slabs(const std::vector<double>& weights, int parts);

}  // namespace hpcplan::dense
