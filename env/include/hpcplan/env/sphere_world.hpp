#pragma once
// The 2D sphere world of seed 003: circular obstacles inside a circular boundary. Free space
// is the closed boundary disc minus the closed obstacle discs, each padded by 1e-9 times the
// boundary radius (see kContactMargin in box_world.hpp).
//
// Threads: immutable once built; any number of threads may query one world at once (the check
// counter is atomic).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hpcplan/core/check_counter.hpp"
#include "hpcplan/env/point.hpp"

namespace hpcplan::env {

struct Circle {
  Vec<2> centre{};
  double radius = 0.0;
  int line = 0;
};

class SphereWorld {
 public:
  static constexpr int kDim = 2;
  using Point = Vec<2>;

  // Throws InputError for a non-positive boundary radius or a negative obstacle radius.
  SphereWorld(Circle boundary, std::vector<Circle> obstacles);

  Aabb<2> bounds() const;
  const Circle& boundary() const { return boundary_; }
  const std::vector<Circle>& obstacles() const { return obstacles_; }

  bool point_free(const Point& p) const;
  bool segment_free(const Point& a, const Point& b) const;
  bool box_free(const Aabb<2>& box) const;
  std::string why_not_free(const Point& p) const;
  double free_volume() const;
  std::uint64_t collision_checks() const { return checks_.value(); }

 private:
  Circle boundary_;
  std::vector<Circle> obstacles_;
  double margin_;        // obstacle padding, as BoxWorld's kContactMargin
  CheckCounter checks_;  // shared by concurrent readers
};

// Text format, one directive per line ('#' comments, blank lines and CRLF accepted):
//   boundary cx cy r     exactly once: the free disc
//   sphere cx cy r       an obstacle disc, any number
//   start x y / goal x y optional query
struct SphereMap {
  SphereWorld world;
  std::optional<Vec<2>> start, goal;
};
SphereMap parse_sphere_map(std::string_view text, const std::string& name);
SphereMap load_sphere_map(const std::string& path);

}  // namespace hpcplan::env
