#include "hpcplan/env/box_world.hpp"

#include <algorithm>
#include <cmath>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/env/segment_box.hpp"

namespace hpcplan::env {

namespace {

bool overlaps(const Aabb<3>& a, const Aabb<3>& b) {
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  return true;
}

void check_box(const Aabb<3>& b, const std::string& what) {
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(b.lo[k]) || !std::isfinite(b.hi[k]))
      throw InputError(what + " has a non-finite coordinate");
    if (b.lo[k] > b.hi[k]) throw InputError(what + " has min > max on axis " + "xyz"[k]);
  }
}

}  // namespace

BoxWorld::BoxWorld(Aabb<3> boundary, std::vector<Block> blocks)
    : boundary_(boundary), blocks_(std::move(blocks)) {
  check_box(boundary_, "the boundary");
  for (int k = 0; k < 3; ++k)
    if (!(boundary_.lo[k] < boundary_.hi[k]))
      throw InputError(std::string("the boundary is empty along axis ") + "xyz"[k]);
  const double margin = kContactMargin * boundary_.largest_side();
  for (const Block& b : blocks_) {
    check_box(b.box, b.line ? "the block of line " + std::to_string(b.line) : "a block");
    Aabb<3> padded = b.box;
    for (int k = 0; k < 3; ++k) padded.lo[k] -= margin, padded.hi[k] += margin;
    boxes_.push_back(padded);
  }
  // About two buckets per block along each axis of the boundary's shape, at most 64 each.
  const double target = std::clamp(static_cast<double>(blocks_.size()) * 8.0, 1.0, 262144.0);
  const double side = std::cbrt(boundary_.volume() / target);
  GridShape<3>::Coords counts;
  for (int k = 0; k < 3; ++k) {
    const double len = boundary_.hi[k] - boundary_.lo[k];
    // Clamped before the conversion: a boundary far longer along one axis than the others
    // (10 x 10 x 1e90) gives a count beyond int's range; NaN (inf / inf) counts as 1.
    const double count = std::ceil(len / side);
    counts[k] = count >= 64.0 ? 64 : count >= 1.0 ? static_cast<int>(count) : 1;
    buckets_.cell[k] = len / static_cast<double>(counts[k]);
  }
  buckets_.origin = boundary_.lo;
  buckets_.shape = GridShape<3>(counts);
  // Closed overlap: a block ending exactly on a bucket face belongs to both buckets; a block
  // wholly outside the boundary cannot touch anything inside it and is in no bucket.
  bucket_items_.build(buckets_.shape.size(), boxes_.size(), [&](std::size_t i, auto&& add) {
    GridShape<3>::Coords first, last;
    if (buckets_.cells_touching(boxes_[i].lo, boxes_[i].hi, first, last))
      GridShape<3>::for_each_in(first, last, [&](const auto& c) { add(buckets_.shape.index(c)); });
  });
  // Free volume (RRT*'s neighbourhood radius scales with it): a fixed stratified sample, so
  // it costs the same for any block count and is the same in every run (within ~1%).
  SplitMix64 rng(0x5eed);
  constexpr int kSide = 24;
  int free = 0;
  for (int i = 0; i < kSide * kSide * kSide; ++i) {
    Point p;
    const int cell[3] = {i % kSide, (i / kSide) % kSide, i / (kSide * kSide)};
    for (int k = 0; k < 3; ++k)
      p[k] = boundary_.lo[k] +
             (cell[k] + rng.next_unit()) / kSide * (boundary_.hi[k] - boundary_.lo[k]);
    free += !any_candidate(Aabb<3>{p, p}, [&](std::uint32_t j) { return boxes_[j].contains(p); });
  }
  free_volume_ = boundary_.volume() * free / (kSide * kSide * kSide);
}

// Calls visit(block index) for every block that may overlap `region` (a superset; blocks
// can repeat) until visit returns true; returns whether one did.
template <class Visit>
bool BoxWorld::any_candidate(const Aabb<3>& region, Visit&& visit) const {
  GridShape<3>::Coords first, last;
  buckets_.cells_touching_clamped(region.lo, region.hi, first, last);
  std::size_t count = 1;
  for (int k = 0; k < 3; ++k) count *= static_cast<std::size_t>(last[k] - first[k] + 1);
  if (count > boxes_.size()) {  // a long query: scanning every block is cheaper
    for (std::uint32_t i = 0; i < boxes_.size(); ++i)
      if (visit(i)) return true;
    return false;
  }
  bool hit = false;
  GridShape<3>::for_each_in(first, last, [&](const auto& c) {
    for (std::uint32_t j : bucket_items_.items_in(buckets_.shape.index(c)))
      if (visit(j)) return !(hit = true);
    return true;
  });
  return hit;
}

bool BoxWorld::point_free(const Point& p) const {
  checks_.add();
  if (!boundary_.contains(p)) return false;
  return !any_candidate(Aabb<3>{p, p}, [&](std::uint32_t i) { return boxes_[i].contains(p); });
}

bool BoxWorld::segment_free(const Point& a, const Point& b) const {
  checks_.add();
  // The boundary is convex: both ends inside keeps the whole segment inside.
  if (!boundary_.contains(a) || !boundary_.contains(b)) return false;
  Aabb<3> region;
  for (int k = 0; k < 3; ++k) {
    region.lo[k] = std::min(a[k], b[k]);
    region.hi[k] = std::max(a[k], b[k]);
  }
  return !any_candidate(region, [&](std::uint32_t i) {
    return overlaps(region, boxes_[i]) && segment_hits_box<3>(a, b, boxes_[i]);
  });
}

bool BoxWorld::box_free(const Aabb<3>& box) const {
  if (!boundary_.contains(box.lo) || !boundary_.contains(box.hi)) return false;
  return !any_candidate(box, [&](std::uint32_t i) { return overlaps(box, boxes_[i]); });
}

std::string BoxWorld::why_not_free(const Point& p) const {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(p[k])) return "not a finite point";
  if (!boundary_.contains(p)) return "outside the boundary";
  for (std::size_t i = 0; i < blocks_.size(); ++i)
    if (boxes_[i].contains(p))
      return blocks_[i].line ? "inside the block of line " + std::to_string(blocks_[i].line)
                             : "inside a block";
  return "";
}

}  // namespace hpcplan::env
