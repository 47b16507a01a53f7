#pragma once
// hpcplan grid --simulate-ranks: the predicted split over P ranks, as the JSON array of
// "rank_simulation" and as a table.
#include <string>

#include <nlohmann/json.hpp>

#include "hpcplan/partition/rank_simulation.hpp"

namespace hpcplan {

nlohmann::json to_json(const partition::RankSimulation& sim);
std::string to_summary(const partition::RankSimulation& sim);

}  // namespace hpcplan
