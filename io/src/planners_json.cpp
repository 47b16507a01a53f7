#include "hpcplan/io/planners_json.hpp"

#include <algorithm>
#include <cstdio>

namespace hpcplan {

namespace {

const char* type_name(plan::ParamType t) {
  switch (t) {
    case plan::ParamType::real:
      return "real";
    case plan::ParamType::integer:
      return "integer";
    case plan::ParamType::flag:
      return "flag";
    case plan::ParamType::choice:
      return "choice";
  }
  return "?";
}

bool shown(const plan::PlannerSpec& s, std::string_view world) {
  return world.empty() || std::find(s.worlds.begin(), s.worlds.end(), world) != s.worlds.end();
}

}  // namespace

nlohmann::json to_json(const plan::PlannerRegistry& registry, std::string_view world) {
  nlohmann::json planners = nlohmann::json::array();
  for (const plan::PlannerSpec& s : registry.planners()) {
    if (!shown(s, world)) continue;
    nlohmann::json params = nlohmann::json::array();
    for (const std::string& name : s.params) {
      const plan::ParamSpec& p = registry.param(name);
      nlohmann::json j = {{"name", p.name},
                          {"option", p.option()},
                          {"type", type_name(p.type)},
                          {"default", p.default_text},
                          {"help", p.help}};
      if (p.type == plan::ParamType::real || p.type == plan::ParamType::integer)
        j["range"] = {p.lo, p.hi};
      if (p.type == plan::ParamType::choice) j["choices"] = p.choices;
      params.push_back(j);
    }
    planners.push_back({{"name", s.name},
                        {"family", s.family},
                        {"worlds", s.worlds},
                        {"help", s.help},
                        {"params", params}});
  }
  return {{"planners", planners}};
}

std::string to_summary(const plan::PlannerRegistry& registry, std::string_view world) {
  std::string out;
  char line[512];
  for (const plan::PlannerSpec& s : registry.planners()) {
    if (!shown(s, world)) continue;
    std::string worlds, params;
    // Appended piecewise: `literal + string` temporaries trip GCC 12's -Wrestrict (bug 105329).
    for (const auto& w : s.worlds) {
      if (!worlds.empty()) worlds += ',';
      worlds += w;
    }
    for (const auto& p : s.params) {
      if (!params.empty()) params += ' ';
      params += registry.param(p).option();
    }
    std::snprintf(line, sizeof line, "%-24s %-16s %-15s %s\n", s.name.c_str(), s.family.c_str(),
                  worlds.c_str(), s.help.c_str());
    out += line;
    if (!params.empty()) out += std::string(58, ' ') + "options: " + params + "\n";
  }
  return out;
}

}  // namespace hpcplan
