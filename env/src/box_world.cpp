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
  std::size_t total = 1;
  for (int k = 0; k < 3; ++k) {
    const double len = boundary_.hi[k] - boundary_.lo[k];
    buckets_[k] = std::clamp(static_cast<int>(std::ceil(len / side)), 1, 64);
    bucket_size_[k] = len / buckets_[k];
    total *= static_cast<std::size_t>(buckets_[k]);
  }
  std::vector<std::vector<std::uint32_t>> lists(total);
  for (std::uint32_t i = 0; i < boxes_.size(); ++i) {
    std::array<int, 3> lo, hi;
    bool outside = false;
    for (int k = 0; k < 3; ++k) {
      const double a = (boxes_[i].lo[k] - boundary_.lo[k]) / bucket_size_[k];
      const double b = (boxes_[i].hi[k] - boundary_.lo[k]) / bucket_size_[k];
      if (b < 0 || a > buckets_[k]) outside = true;
      // Closed overlap: a block ending exactly on a bucket face belongs to both buckets.
      lo[k] = std::clamp(static_cast<int>(std::floor(a)) - (a == std::floor(a) ? 1 : 0), 0,
                         buckets_[k] - 1);
      hi[k] = std::clamp(static_cast<int>(std::floor(b)), 0, buckets_[k] - 1);
    }
    if (outside) continue;  // cannot touch anything inside the boundary
    for (int x = lo[0]; x <= hi[0]; ++x)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int z = lo[2]; z <= hi[2]; ++z)
          lists[(static_cast<std::size_t>(z) * buckets_[1] + y) * buckets_[0] + x].push_back(i);
  }
  bucket_start_.reserve(total + 1);
  bucket_start_.push_back(0);
  for (const auto& l : lists) {
    bucket_items_.insert(bucket_items_.end(), l.begin(), l.end());
    bucket_start_.push_back(static_cast<std::uint32_t>(bucket_items_.size()));
  }
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
  std::array<int, 3> lo, hi;
  std::size_t count = 1;
  for (int k = 0; k < 3; ++k) {
    const double a = (region.lo[k] - boundary_.lo[k]) / bucket_size_[k];
    const double b = (region.hi[k] - boundary_.lo[k]) / bucket_size_[k];
    lo[k] = std::clamp(static_cast<int>(std::floor(a)) - (a == std::floor(a) ? 1 : 0), 0,
                       buckets_[k] - 1);
    hi[k] = std::clamp(static_cast<int>(std::floor(b)), 0, buckets_[k] - 1);
    count *= static_cast<std::size_t>(hi[k] - lo[k] + 1);
  }
  if (count > boxes_.size()) {  // a long query: scanning every block is cheaper
    for (std::uint32_t i = 0; i < boxes_.size(); ++i)
      if (visit(i)) return true;
    return false;
  }
  for (int z = lo[2]; z <= hi[2]; ++z)
    for (int y = lo[1]; y <= hi[1]; ++y)
      for (int x = lo[0]; x <= hi[0]; ++x) {
        const std::size_t b = (static_cast<std::size_t>(z) * buckets_[1] + y) * buckets_[0] + x;
        for (std::uint32_t j = bucket_start_[b]; j < bucket_start_[b + 1]; ++j)
          if (visit(bucket_items_[j])) return true;
      }
  return false;
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
