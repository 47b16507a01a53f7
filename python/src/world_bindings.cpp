// hpcplan.map3d and hpcplan.sphere2d: a world file loaded once (seed 004's box maps, seed
// 003's sphere worlds), planned in with any world planner (hpcplan map3d / sphere2d's options
// and answers), and queried in bulk.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "bridge.hpp"
#include "hpcplan/cli/point_option.hpp"
#include "hpcplan/cli/world_options.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/env/box_map_io.hpp"
#include "hpcplan/env/sphere_world.hpp"
#include "hpcplan/io/world_plan_json.hpp"
#include "hpcplan/plan/world_planner.hpp"

namespace hpcplan::python {

namespace {

// A loaded world file (immutable: any number of threads may plan in it at once).
template <class Map>
struct World {
  std::shared_ptr<const Map> map;
  std::string path;
};

template <class Map>
constexpr int kDimOf = std::remove_cvref_t<decltype(std::declval<Map>().world)>::kDim;

// A point given from Python, read as the CLI reads --start and --goal: its coordinates
// written as that option's text and parsed by the CLI's own parser (cli/point_option.hpp), so
// a wrong count or a non-finite coordinate gets the CLI's message.
template <int D>
env::Vec<D> point_of(const py::handle& value, const char* option) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a || a.ndim() != 1)
    throw InputError(std::string(option) + " needs " + std::to_string(D) +
                     " comma-separated coordinates");
  std::string text;
  for (py::ssize_t k = 0; k < a.shape(0); ++k) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", a.data()[k]);
    text += (k ? "," : "") + std::string(buf);
  }
  return cli::parse_point<D>(text, option);
}

template <int D>
py::object point_or_none(const std::optional<env::Vec<D>>& p) {
  if (!p) return py::none();
  py::array_t<double> a(D);
  std::copy(p->begin(), p->end(), a.mutable_data());
  return a;
}

template <class Map>
py::tuple plan(const World<Map>& w, const py::object& start, const py::object& goal,
               const std::vector<std::string>& tokens, const StopSource* stop,
               const std::string& world_name) {
  constexpr int D = kDimOf<Map>;
  plan::WorldPlanOptions options = parse_cached<plan::WorldPlanOptions>(
      "hpcplan " + world_name, tokens, [&](CLI::App* c, plan::WorldPlanOptions& o) {
        cli::add_world_planner_options(c, o, world_name);
      });
  // The CLI's rule: the point given, else the map's own line.
  auto query = [&](const py::object& given, const std::optional<env::Vec<D>>& from_map,
                   const char* option, const char* what) {
    if (!given.is_none()) return point_of<D>(given, option);
    if (from_map) return *from_map;
    throw InputError(std::string("no ") + option + " given and the map has no " + what + " line");
  };
  const env::Vec<D> a = query(start, w.map->start, "--start", "start");
  const env::Vec<D> b = query(goal, w.map->goal, "--goal", "goal");
  struct Answer {
    plan::WorldPlan<D> plan;
    nlohmann::json json;
  };
  Answer answer = call_released<Answer>(
      [&](const cli::RunControl& control) {
        options.cancel = control.cancel;
        Answer r;
        r.plan = plan::plan_in_world(w.map->world, a, b, options);
        r.json = to_json(r.plan);
        r.json.erase("path");  // given as an array instead
        return r;
      },
      stop);
  py::array_t<double> path(
      {static_cast<py::ssize_t>(answer.plan.path.size()), static_cast<py::ssize_t>(D)});
  double* out = path.mutable_data();
  for (const env::Vec<D>& p : answer.plan.path) out = std::copy(p.begin(), p.end(), out);
  return py::make_tuple(to_python(answer.json), std::move(path));
}

// Free or not, per point of an (n, D) array (or one point of shape (D,)), by the world's exact
// point test (on the boundary or a block's face counts as touching it).
template <class Map>
py::object points_free(const World<Map>& w, const py::array& points) {
  constexpr int D = kDimOf<Map>;
  const auto p = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points);
  if (!p || !(p.ndim() == 1 || p.ndim() == 2) || p.shape(p.ndim() - 1) != D)
    throw InputError("points must have shape (" + std::to_string(D) + ",) or (n, " +
                     std::to_string(D) + ")");
  const py::ssize_t n = p.ndim() == 1 ? 1 : p.shape(0);
  py::array_t<bool> out(n);
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < n; ++i) {
      env::Vec<D> q;
      std::copy_n(p.data() + i * D, D, q.begin());
      // A point that is not finite is nowhere in the world: not free.
      const bool finite =
          std::all_of(q.begin(), q.end(), [](double c) { return std::isfinite(c); });
      out.mutable_data()[i] = finite && w.map->world.point_free(q);
    }
  }
  if (p.ndim() == 1) return py::bool_(out.data()[0]);
  return out;
}

template <class Map, class Load, class Describe>
py::class_<World<Map>> bind_world(py::module_& m, const char* class_name,
                                  const std::string& world_name, Load load,
                                  Describe describe_obstacles) {
  using W = World<Map>;
  constexpr int D = kDimOf<Map>;
  m.def((world_name + "_options").c_str(), [world_name] {
    return describe_options<plan::WorldPlanOptions>(
        "hpcplan " + world_name, [&](CLI::App* c, plan::WorldPlanOptions& o) {
          cli::add_world_planner_options(c, o, world_name);
        });
  });
  py::class_<W> c(m, class_name);
  c.def(py::init([load](const std::string& path) {
          // The file checked as the CLI checks --map, with its message.
          const std::string problem = CLI::ExistingFile(path);
          if (!problem.empty()) throw InputError("--map: " + problem);
          return W{std::make_shared<const Map>(load(path)), path};
        }),
        py::arg("path"))
      .def_readonly("path", &W::path)
      .def_property_readonly("start", [](const W& w) { return point_or_none<D>(w.map->start); })
      .def_property_readonly("goal", [](const W& w) { return point_or_none<D>(w.map->goal); })
      .def_property_readonly("bounds",
                             [](const W& w) {
                               const auto b = w.map->world.bounds();
                               py::array_t<double> a({2, D});
                               std::copy(b.lo.begin(), b.lo.end(), a.mutable_data());
                               std::copy(b.hi.begin(), b.hi.end(), a.mutable_data() + D);
                               return a;
                             })
      .def_property_readonly(
          "obstacles", [describe_obstacles](const W& w) { return describe_obstacles(*w.map); })
      .def("free", &points_free<Map>, py::arg("points"))
      .def(
          "segment_free",
          [](const W& w, const py::object& a, const py::object& b) {
            return w.map->world.segment_free(point_of<D>(a, "a"), point_of<D>(b, "b"));
          },
          py::arg("a"), py::arg("b"))
      .def(
          "plan",
          [world_name](const W& w, const py::object& start, const py::object& goal,
                       const std::vector<std::string>& tokens, const StopSource* stop) {
            return plan<Map>(w, start, goal, tokens, stop, world_name);
          },
          py::arg("start"), py::arg("goal"), py::arg("tokens"), py::arg("stop") = nullptr);
  return c;
}

}  // namespace

void bind_worlds(py::module_& m) {
  // Box maps: the blocks as an (n, 6) array of lo x, y, z, hi x, y, z.
  auto box_map =
      bind_world<env::BoxMap>(m, "BoxMap", "map3d", env::load_box_map, [](const env::BoxMap& map) {
        const auto& blocks = map.world.blocks();
        py::array_t<double> a({static_cast<py::ssize_t>(blocks.size()), py::ssize_t{6}});
        double* out = a.mutable_data();
        for (const env::Block& b : blocks) {
          out = std::copy(b.box.lo.begin(), b.box.lo.end(), out);
          out = std::copy(b.box.hi.begin(), b.box.hi.end(), out);
        }
        return a;
      });
  // Sphere worlds: the obstacles as an (n, 3) array of centre x, y and radius.
  // The blocks' colours (r, g, b as the file gives them; grey when it gives none).
  box_map.def_property_readonly("colours", [](const World<env::BoxMap>& w) {
    const auto& blocks = w.map->world.blocks();
    py::array_t<double> a({static_cast<py::ssize_t>(blocks.size()), py::ssize_t{3}});
    double* out = a.mutable_data();
    for (const env::Block& b : blocks) out = std::copy(b.rgb.begin(), b.rgb.end(), out);
    return a;
  });
  auto sphere_map = bind_world<env::SphereMap>(
      m, "SphereMap", "sphere2d", env::load_sphere_map, [](const env::SphereMap& map) {
        const auto& circles = map.world.obstacles();
        py::array_t<double> a({static_cast<py::ssize_t>(circles.size()), py::ssize_t{3}});
        double* out = a.mutable_data();
        for (const env::Circle& c : circles) {
          *out++ = c.centre[0];
          *out++ = c.centre[1];
          *out++ = c.radius;
        }
        return a;
      });
  // The circular boundary: centre x, y and radius.
  sphere_map.def_property_readonly("boundary", [](const World<env::SphereMap>& w) {
    const env::Circle& b = w.map->world.boundary();
    py::array_t<double> a(3);
    a.mutable_data()[0] = b.centre[0];
    a.mutable_data()[1] = b.centre[1];
    a.mutable_data()[2] = b.radius;
    return a;
  });
}

}  // namespace hpcplan::python
