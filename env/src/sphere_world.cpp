#include "hpcplan/env/sphere_world.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/text_lines.hpp"

namespace hpcplan::env {

namespace {

double squared(double x) {
  return x * x;
}

double distance_squared(const Vec<2>& a, const Vec<2>& b) {
  return squared(a[0] - b[0]) + squared(a[1] - b[1]);
}

// Squared distance from c to the closed segment a-b.
double segment_distance_squared(const Vec<2>& a, const Vec<2>& b, const Vec<2>& c) {
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((c[0] - a[0]) * dx + (c[1] - a[1]) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return distance_squared({a[0] + t * dx, a[1] + t * dy}, c);
}

}  // namespace

SphereWorld::SphereWorld(Circle boundary, std::vector<Circle> obstacles)
    : boundary_(boundary), obstacles_(std::move(obstacles)), margin_(1e-9 * boundary.radius) {
  if (!(boundary_.radius > 0)) throw InputError("the boundary radius must be positive");
  for (const Circle& c : obstacles_)
    if (c.radius < 0)
      throw InputError("the sphere of line " + std::to_string(c.line) + " has a negative radius");
}

Aabb<2> SphereWorld::bounds() const {
  const double r = boundary_.radius;
  return {{boundary_.centre[0] - r, boundary_.centre[1] - r},
          {boundary_.centre[0] + r, boundary_.centre[1] + r}};
}

bool SphereWorld::point_free(const Point& p) const {
  checks_.add();
  if (distance_squared(p, boundary_.centre) > squared(boundary_.radius)) return false;
  for (const Circle& c : obstacles_)
    if (distance_squared(p, c.centre) <= squared(c.radius + margin_)) return false;
  return true;
}

bool SphereWorld::segment_free(const Point& a, const Point& b) const {
  checks_.add();
  // The boundary disc is convex: both ends inside keeps the segment inside.
  const double r2 = squared(boundary_.radius);
  if (distance_squared(a, boundary_.centre) > r2 || distance_squared(b, boundary_.centre) > r2)
    return false;
  for (const Circle& c : obstacles_)
    if (segment_distance_squared(a, b, c.centre) <= squared(c.radius + margin_)) return false;
  return true;
}

bool SphereWorld::box_free(const Aabb<2>& box) const {
  const double r2 = squared(boundary_.radius);
  for (int corner = 0; corner < 4; ++corner) {
    const Vec<2> p{corner & 1 ? box.hi[0] : box.lo[0], corner & 2 ? box.hi[1] : box.lo[1]};
    if (distance_squared(p, boundary_.centre) > r2) return false;
  }
  for (const Circle& c : obstacles_) {
    const Vec<2> nearest{std::clamp(c.centre[0], box.lo[0], box.hi[0]),
                         std::clamp(c.centre[1], box.lo[1], box.hi[1])};
    if (distance_squared(nearest, c.centre) <= squared(c.radius + margin_)) return false;
  }
  return true;
}

std::string SphereWorld::why_not_free(const Point& p) const {
  if (!std::isfinite(p[0]) || !std::isfinite(p[1])) return "not a finite point";
  if (distance_squared(p, boundary_.centre) > squared(boundary_.radius))
    return "outside the boundary";
  for (const Circle& c : obstacles_)
    if (distance_squared(p, c.centre) <= squared(c.radius + margin_))
      return c.line ? "inside the sphere of line " + std::to_string(c.line) : "inside a sphere";
  return "";
}

double SphereWorld::free_volume() const {
  // Obstacles may overlap or poke out of the boundary; subtracting their full areas keeps
  // this a lower bound, which is what the RRT* radius needs (a larger gamma is still safe).
  double v = std::numbers::pi * squared(boundary_.radius);
  for (const Circle& c : obstacles_) v -= std::numbers::pi * squared(c.radius);
  return std::max(v, 0.05 * std::numbers::pi * squared(boundary_.radius));
}

SphereMap parse_sphere_map(std::string_view text, const std::string& name) {
  std::optional<Circle> boundary;
  std::vector<Circle> obstacles;
  std::optional<Vec<2>> start, goal;
  for_each_directive(text, name, [&](int line, const std::vector<std::string_view>& w) {
    const std::string_view key = w[0];
    if (key == "boundary" || key == "sphere") {
      if (w.size() != 4) throw InputError(where(name, line) + std::string(key) + " needs cx cy r");
      Circle c{{parse_number(w[1], name, line), parse_number(w[2], name, line)},
               parse_number(w[3], name, line),
               line};
      if (key == "boundary") {
        if (boundary) throw InputError(where(name, line) + "a second boundary line");
        if (!(c.radius > 0))
          throw InputError(where(name, line) + "the boundary radius must be positive");
        boundary = c;
      } else {
        if (c.radius < 0)
          throw InputError(where(name, line) + "a sphere radius must not be negative");
        obstacles.push_back(c);
      }
    } else if (key == "start" || key == "goal") {
      if (w.size() != 3) throw InputError(where(name, line) + std::string(key) + " needs x y");
      auto& slot = key == "start" ? start : goal;
      if (slot) throw InputError(where(name, line) + "a second " + std::string(key) + " line");
      slot = Vec<2>{parse_number(w[1], name, line), parse_number(w[2], name, line)};
    } else {
      throw InputError(where(name, line) + "unknown directive '" + std::string(key) +
                       "' (expected boundary, sphere, start or goal)");
    }
  });
  if (!boundary) throw InputError(name + ": no boundary line");
  return SphereMap{SphereWorld(*boundary, std::move(obstacles)), start, goal};
}

SphereMap load_sphere_map(const std::string& path) {
  return parse_sphere_map(read_text_file(path, "sphere world file"), path);
}

}  // namespace hpcplan::env
