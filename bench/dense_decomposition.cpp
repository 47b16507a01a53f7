// The dense engine's decomposition of a GOG lattice over P ranks, rank by rank, without
// allocating the lattice (dense::describe_decomposition): the input of the scaling model of
// bench/dense_blocks.py, for machines this one cannot run (6D extent 100 on 64 to 512 ranks).
//   hpcplan_dense_decomposition --dims D --extent E --ranks P[,P...] [--threads T]
//                               [--algo bfs|dijkstra] [--seed S]
// Prints one JSON object per P: the cut, and per rank its tiles, sections, peers, ghost tiles
// and planned bytes. The field is the CLI's GOG field of that seed (its default parameters).
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hpcplan/core/error.hpp"
#include "hpcplan/dense/dense_search.hpp"
#include "hpcplan/env/gog.hpp"

int main(int argc, char** argv) {
  using namespace hpcplan;
  int dims = 0, extent = 0, threads = 1;
  std::uint64_t seed = GogParams{}.seed;
  std::vector<int> ranks;
  std::string algo = "bfs";
  for (int i = 1; i < argc; i += 2) {
    const std::string a = argv[i];
    if (i + 1 == argc) {
      std::fprintf(stderr, "hpcplan_dense_decomposition: %s needs a value\n", a.c_str());
      return 2;
    }
    const std::string v = argv[i + 1];
    if (a == "--dims") {
      dims = std::atoi(v.c_str());
    } else if (a == "--extent") {
      extent = std::atoi(v.c_str());
    } else if (a == "--threads") {
      threads = std::atoi(v.c_str());
    } else if (a == "--seed") {
      seed = std::strtoull(v.c_str(), nullptr, 10);
    } else if (a == "--algo") {
      algo = v;
    } else if (a == "--ranks") {
      std::stringstream in(v);
      for (std::string p; std::getline(in, p, ',');) ranks.push_back(std::atoi(p.c_str()));
    } else {
      std::fprintf(stderr, "hpcplan_dense_decomposition: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  if (dims < 1 || dims > 16 || extent < 2 || ranks.empty() || threads < 1 ||
      (algo != "bfs" && algo != "dijkstra")) {
    std::fprintf(stderr,
                 "hpcplan_dense_decomposition: give --dims 1..16, --extent >= 2, --ranks P[,P...]"
                 " (--threads >= 1, --algo bfs|dijkstra)\n");
    return 2;
  }
  try {
    GogParams g;
    g.seed = seed;
    const GogField field(dims, extent, g);
    dense::Query q;
    q.threads = threads;
    q.algorithm = algo == "bfs" ? dense::Algorithm::bfs : dense::Algorithm::dijkstra;
    for (const int p : ranks) {
      if (p < 1) throw InputError("--ranks: every count must be at least 1");
      const dense::Decomposition d = dense::describe_decomposition(field, q, p);
      nlohmann::json j = {{"ranks", p},
                          {"threads", threads},
                          {"cut_axis", d.cut_axis},
                          {"section_tiles", d.section_tiles},
                          {"block_sections", d.block_sections},
                          {"blocks", d.blocks},
                          {"free_states", d.free_states}};
      for (const dense::RankPlan& r : d.ranks) {
        j["tiles"].push_back(r.tiles);
        j["sections"].push_back(r.sections);
        j["peers"].push_back(r.peers);
        j["ghost_tiles"].push_back(r.ghost_tiles);
        j["planned_bytes"].push_back(r.planned_bytes);
      }
      std::cout << j.dump() << "\n";
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hpcplan_dense_decomposition: %s\n", e.what());
    return 2;
  }
  return 0;
}
