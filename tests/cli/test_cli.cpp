// The `hpcplan grid` contract, exercised through the real executable.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "hpcplan/env/gog.hpp"

namespace {

struct CliRun {
  int code = -1;
  std::string out, err;
};

// `prefix`: shell commands run before the executable (exec'd in the same shell).
CliRun run(const std::string& args, const std::string& prefix = "") {
  const auto dir = std::filesystem::temp_directory_path();
  const std::string err_file = (dir / ("hpcplan_cli_err_" + std::to_string(::getpid()))).string();
  const std::string cmd =
      prefix + (prefix.empty() ? "" : " exec ") + HPCPLAN_BIN + " " + args + " 2>" + err_file;
  CliRun r;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) r.out.append(buf, n);
  const int status = ::pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err_file);
  std::stringstream ss;
  ss << e.rdbuf();
  r.err = ss.str();
  std::filesystem::remove(err_file);
  return r;
}

std::string read_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void expect_bad_input(const std::string& args, const std::string& mentions) {
  const CliRun r = run(args);
  EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
  EXPECT_TRUE(r.out.empty()) << args;
  // One line, naming the problem.
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(mentions), std::string::npos) << args << " -> " << r.err;
}

TEST(Cli, JsonHasTheDocumentedKeys) {
  const CliRun r = run("grid --dims 3 --json --path");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"status",      "dims",    "algo",     "weight",    "heuristic",
                          "seed",        "extent",  "start",    "goal",      "cost",
                          "hops",        "quality", "expanded", "generated", "collision_checks",
                          "peak_states", "time_ms", "ranks",    "path",      "blocked_fraction",
                          "threshold"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["status"], "solved");
  EXPECT_EQ(j["ranks"], 1);
  EXPECT_EQ(j["path"].size(), j["hops"].get<std::size_t>() + 1);
  EXPECT_EQ(j["path"].front(), j["start"]);
  EXPECT_EQ(j["path"].back(), j["goal"]);
}

TEST(Cli, EveryAlgorithmRunsAndAgreesOnCost) {
  double astar_cost = 0;
  for (const char* algo : {"astar", "dijkstra", "wastar", "bfs"}) {
    const CliRun r = run(std::string("grid --dims 2 --extent 40 --json --algo ") + algo);
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["algo"], algo);
    const double cost = j["cost"];
    if (std::string(algo) == "astar") astar_cost = cost;
    if (std::string(algo) == "dijkstra") {
      EXPECT_NEAR(cost, astar_cost, 1e-9);
    }
    if (std::string(algo) == "wastar") {
      EXPECT_LE(cost, 2.0 * astar_cost + 1e-9);
    }
  }
}

// 2D A* prunes with jump points unless told not to; both give the same optimum, and both paths
// are unit moves from start to goal.
TEST(Cli, JumpPointsCanBeSwitchedOff) {
  const CliRun pruned = run("grid --dims 2 --json --path");
  const CliRun plain = run("grid --dims 2 --json --path --no-jump-points");
  ASSERT_EQ(pruned.code, 0) << pruned.err;
  ASSERT_EQ(plain.code, 0) << plain.err;
  const auto a = nlohmann::json::parse(pruned.out);
  const auto b = nlohmann::json::parse(plain.out);
  EXPECT_EQ(a["pruning"], "jump_points");
  EXPECT_EQ(b["pruning"], "none");
  EXPECT_NEAR(a["cost"].get<double>(), b["cost"].get<double>(), 1e-9);
  EXPECT_LT(a["expanded"].get<std::uint64_t>(), b["expanded"].get<std::uint64_t>());
  for (const auto* j : {&a, &b}) {
    const auto& path = (*j)["path"];
    ASSERT_EQ(path.size(), (*j)["hops"].get<std::size_t>() + 1);
    for (std::size_t i = 1; i < path.size(); ++i)
      for (int axis = 0; axis < 2; ++axis)
        EXPECT_LE(std::abs(path[i][axis].get<int>() - path[i - 1][axis].get<int>()), 1);
  }
  const CliRun summary = run("grid --dims 2");
  EXPECT_TRUE(std::regex_search(summary.out, std::regex("pruning +jump_points"))) << summary.out;
}

TEST(Cli, SummaryIsReadable) {
  const CliRun r = run("grid --dims 2");
  ASSERT_EQ(r.code, 0);
  EXPECT_TRUE(std::regex_search(r.out, std::regex("(^|\\n) *status +solved\\n"))) << r.out;
  EXPECT_NE(r.out.find("quality"), std::string::npos);
}

TEST(Cli, NoPathAndBudgetAreValidAnswers) {
  // Find a 1D field with a wall between the ends.
  bool found = false;
  for (std::uint64_t seed = 1; seed < 500 && !found; ++seed) {
    hpcplan::GogParams p;
    p.seed = seed;
    p.threshold = 2;
    const hpcplan::GogField f(1, 64, p);
    bool wall = false;
    for (int c = 1; c < 63; ++c) wall = wall || !f.is_free(std::vector<int>{c});
    if (!wall || !f.is_free(std::vector<int>{0}) || !f.is_free(std::vector<int>{63})) continue;
    const CliRun r =
        run("grid --dims 1 --extent 64 --threshold 2 --start 0 --goal 63 --json --seed " +
            std::to_string(seed));
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["status"], "no_path");
    EXPECT_TRUE(nlohmann::json::parse(r.out)["cost"].is_null());
    found = true;
  }
  ASSERT_TRUE(found) << "no walled 1D field among the seeds tried";
  const CliRun b = run("grid --dims 4 --max-states 5 --json");
  EXPECT_EQ(b.code, 0);
  EXPECT_EQ(nlohmann::json::parse(b.out)["status"], "budget_exceeded");
}

TEST(Cli, BadInputExitsTwoWithOneLine) {
  expect_bad_input("grid --dims 0", "--dims");
  expect_bad_input("grid --dims 17", "--dims");
  expect_bad_input("grid --dims abc", "dims");
  expect_bad_input("grid --dims 2 --extent 1", "--extent");
  expect_bad_input("grid --dims 2 --extent 65536", "--extent");
  // CLI11 would read "010" as octal 8: an integer with a leading zero is refused.
  expect_bad_input("grid --dims 2 --extent 010", "leading zero");
  expect_bad_input("grid --dims 2 --simulate-ranks 2,04", "leading zero");
  expect_bad_input("grid --dims 2 --start 1,2,3", "--start");
  expect_bad_input("grid --dims 2 --start 1,x", "--start");
  expect_bad_input("grid --dims 2 --goal 5,100", "outside the box");
  expect_bad_input("grid --dims 2 --start -1,0", "outside the box");
  expect_bad_input("grid --dims 2 --algo wastar --weight 0.5", "--weight");
  expect_bad_input("grid --dims 2 --algo dfs", "unknown algorithm");
  expect_bad_input("grid --dims 2 --heuristic manhattan", "unknown heuristic");
  expect_bad_input("grid --dims 2 --frobnicate", "frobnicate");
  expect_bad_input("grid --dims 5 --connectivity full", "full");
  expect_bad_input("grid --dims 2 --threshold 99", "--threshold");
  expect_bad_input("grid", "dims");
  expect_bad_input("", "subcommand");
  expect_bad_input("grid --dims 2 --simulate-ranks 0", "--simulate-ranks");
  expect_bad_input("grid --dims 2 --simulate-ranks 2 --simulate-coarsen 17", "--simulate-coarsen");
  expect_bad_input("grid --dims 2 --owner-slabs 2 --owner-coarsen 1", "--owner-slabs");
  expect_bad_input("grid --dims 2 --extent 50 --owner-slabs 51", "wider than the extent");
  // Prefix cuts: P - 1 of them (a plain run has one rank), strictly inside extent^2.
  expect_bad_input("grid --dims 2 --owner-cuts 5", "--owner-cuts needs P - 1 positions");
  expect_bad_input("grid --dims 2 --extent 10 --owner-cuts 100", "--owner-cuts must ascend");
  expect_bad_input("grid --dims 2 --owner-cuts 5 --owner-slabs 2", "--owner-cuts replaces");
}

// The dense engine from the command line: chosen for BFS and Dijkstra, its figures in the JSON,
// the sparse engine's hops and costs, and its options refused clearly.
TEST(Cli, DenseEngineRunsBfsAndDijkstra) {
  for (const char* algo : {"bfs", "dijkstra"}) {
    const std::string base = std::string("grid --dims 4 --extent 13 --json --path --algo ") + algo;
    const CliRun a = run(base);
    const CliRun d = run(base + " --engine dense --threads 2 --slab-layers 2");
    const CliRun c = run(base + " --engine dense --contiguous-slabs");
    const CliRun s = run(base + " --engine sparse");
    for (const CliRun* r : {&a, &d, &c, &s}) ASSERT_EQ(r->code, 0) << r->err;
    const auto ja = nlohmann::json::parse(a.out), jd = nlohmann::json::parse(d.out),
               jc = nlohmann::json::parse(c.out), js = nlohmann::json::parse(s.out);
    EXPECT_EQ(ja["engine"], "dense") << algo;  // auto: the lattice fits
    EXPECT_EQ(js["engine"], "sparse") << algo;
    EXPECT_FALSE(js.contains("dense"));
    for (const auto* j : {&ja, &jd, &jc}) {
      EXPECT_EQ((*j)["visited_map"], "dense_bitmap");
      for (const char* key : {"tile", "tiles", "free_states", "reached", "bytes_per_rank",
                              "bytes_total", "levels", "threads", "blocks", "block_sections"})
        EXPECT_TRUE((*j)["dense"].contains(key)) << key;
      EXPECT_EQ((*j)["hops"], js["hops"]) << algo;
      EXPECT_EQ((*j)["path"].size(), (*j)["hops"].get<std::size_t>() + 1);
      EXPECT_EQ((*j)["path"], ja["path"]) << algo << ": the same path whatever the layout";
    }
    EXPECT_EQ(jd["dense"]["block_sections"], 2);
    EXPECT_EQ(jd["dense"]["threads"], 2);
    EXPECT_EQ(jc["dense"]["block_sections"], 0);
    if (std::string(algo) == "dijkstra") {
      EXPECT_NEAR(ja["cost"], js["cost"], 1e-9);
    }
  }
  expect_bad_input("grid --dims 2 --engine quantum", "--engine");
  expect_bad_input("grid --dims 2 --engine dense", "--engine dense runs --algo bfs and dijkstra");
  expect_bad_input("grid --dims 2 --algo bfs --slab-layers 2 --contiguous-slabs",
                   "--contiguous-slabs");
  // Over the budget: one line with the bytes needed and the budget, before anything runs.
  expect_bad_input("grid --dims 5 --extent 100 --algo bfs --engine dense --memory-budget 1000000",
                   "over the budget of 1 MB (1000000 bytes)");
  // A start inside an obstacle is bad input for the dense engine too.
  const hpcplan::GogField f(2, 100, {});
  std::vector<int> blocked{0, 0};
  for (int i = 0; f.is_free(blocked); ++i) blocked = {i % 100, i / 100};
  expect_bad_input("grid --dims 2 --algo bfs --engine dense --start " + std::to_string(blocked[0]) +
                       "," + std::to_string(blocked[1]),
                   "inside an obstacle");
}

// The dense engine's limits: a process whose OpenMP runtime starts fewer threads than asked
// runs with what it has (once the missing threads' blocks were silently skipped: no_path), a
// lattice too large for any tile index is refused for --engine dense and left to the sparse
// engine by auto (once an overflowing tile count crashed the default run).
TEST(Cli, DenseEngineKeepsWithinItsLimits) {
  const std::string q = "grid --dims 3 --extent 30 --algo bfs --engine dense --json";
  const CliRun one = run(q + " --threads 1");
  ::setenv("OMP_THREAD_LIMIT", "1", 1);
  const CliRun limited = run(q + " --threads 2 --slab-layers 4");
  ::unsetenv("OMP_THREAD_LIMIT");
  ASSERT_EQ(one.code, 0) << one.err;
  ASSERT_EQ(limited.code, 0) << limited.err;
  const auto jo = nlohmann::json::parse(one.out), jl = nlohmann::json::parse(limited.out);
  EXPECT_EQ(jl["status"], "solved");
  EXPECT_EQ(jl["dense"]["threads"], 1);
  EXPECT_EQ(jl["cost"], jo["cost"]);
  expect_bad_input("grid --dims 12 --extent 64 --algo dijkstra --engine dense",
                   "too large for the dense engine");
  const CliRun big = run("grid --dims 16 --extent 32 --algo bfs --max-states 1000 --json");
  ASSERT_EQ(big.code, 0) << big.err;
  const auto jb = nlohmann::json::parse(big.out);
  EXPECT_EQ(jb["engine"], "sparse");
  EXPECT_EQ(jb["status"], "budget_exceeded");
}

// The rank simulator's report: shares per split are consistent with the observed search.
TEST(Cli, SimulateRanksReportsEverySplit) {
  const CliRun r =
      run("grid --dims 3 --extent 30 --algo dijkstra --simulate-ranks 1,2,64 "
          "--simulate-coarsen 0,2 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["rank_simulation"].size(), 6u);
  const double expanded = j["expanded"].get<double>();
  for (const auto& s : j["rank_simulation"]) {
    const int p = s["ranks"];
    EXPECT_GE(s["max_expanded_per_rank"].get<double>() * p, expanded - 1e-9);
    EXPECT_LE(s["min_expanded_per_rank"].get<double>() * p, expanded + 1e-9);
    EXPECT_GE(s["imbalance"].get<double>(), 1.0 - 1e-12);
    if (p == 1) {
      EXPECT_EQ(s["remote_successors"], 0);
      EXPECT_EQ(s["expansion_deviation_percent"], 0.0);
    } else {
      EXPECT_GT(s["remote_successors"].get<double>(), 0.0);
    }
  }
  // Cells of 4^3 states keep more successors local than the state hash.
  EXPECT_LT(j["rank_simulation"][4]["remote_fraction"].get<double>(),
            j["rank_simulation"][1]["remote_fraction"].get<double>());
  // The balanced prefix cuts: P - 1 ascending positions inside the 30^2 of the first two axes.
  for (const auto& s : j["rank_simulation"]) {
    const auto cuts = s["balanced_prefix_cuts"].get<std::vector<int>>();
    ASSERT_EQ(cuts.size(), s["ranks"].get<std::size_t>() - 1);
    for (std::size_t i = 0; i < cuts.size(); ++i) {
      EXPECT_GE(cuts[i], i == 0 ? 1 : cuts[i - 1] + 1);
      EXPECT_LT(cuts[i], 900);
    }
  }
  const CliRun table = run("grid --dims 3 --extent 30 --algo dijkstra --simulate-ranks 2");
  ASSERT_EQ(table.code, 0) << table.err;
  EXPECT_NE(table.out.find("balanced --owner-cuts for 2 ranks: "), std::string::npos) << table.out;
}

TEST(Cli, OutputFileIsWrittenWholeOrNotAtAll) {
  const auto dir = std::filesystem::temp_directory_path() / "hpcplan_cli_out";
  std::filesystem::create_directories(dir);
  const auto file = dir / "result.json";
  std::filesystem::remove(file);
  CliRun r = run("grid --dims 2 --output " + file.string());
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(file);
  EXPECT_EQ(nlohmann::json::parse(in)["status"], "solved");
  // A bad request leaves the previous result untouched and no temporary behind.
  const std::string before = read_file(file);
  r = run("grid --dims 0 --output " + file.string());
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(read_file(file), before);
  ASSERT_FALSE(before.empty());
  // A destination that cannot exist is bad input, refused before the run (exit 2).
  r = run("grid --dims 2 --output /nonexistent-dir/x.json");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("/nonexistent-dir/x.json"), std::string::npos);
  EXPECT_NE(r.err.find("does not exist"), std::string::npos);
  r = run("grid --dims 2 --output " + dir.string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("is a directory"), std::string::npos);
  std::size_t entries = 0;
  for ([[maybe_unused]] auto& e : std::filesystem::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 1u);
}

// hpcplan planners: the registry, readable and as JSON, whole or for one setting; an unknown
// setting is bad input.
TEST(Cli, PlannersListsTheRegistry) {
  const CliRun text = run("planners");
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("astar"), std::string::npos) << text.out;
  const CliRun all = run("planners --json");
  ASSERT_EQ(all.code, 0) << all.err;
  const auto j = nlohmann::json::parse(all.out);
  ASSERT_TRUE(j.contains("planners")) << all.out.substr(0, 200);
  std::set<std::string> worlds;
  for (const auto& p : j["planners"]) {
    ASSERT_TRUE(p.contains("name") && p.contains("worlds") && p.contains("params")) << p.dump();
    for (const auto& w : p["worlds"]) worlds.insert(w.get<std::string>());
    EXPECT_NE(text.out.find(p["name"].get<std::string>()), std::string::npos) << p["name"];
    for (const auto& param : p["params"])  // each with its CLI option and, if numeric, range
      EXPECT_TRUE(param.contains("option") &&
                  (param["type"] == "flag" || param["type"] == "choice" || param.contains("range")))
          << param.dump();
  }
  EXPECT_EQ(worlds, (std::set<std::string>{"grid", "map3d", "sphere2d", "ompl", "sim"}));
  const CliRun sim = run("planners --world sim --json");
  ASSERT_EQ(sim.code, 0) << sim.err;
  const auto js = nlohmann::json::parse(sim.out);
  ASSERT_FALSE(js["planners"].empty());
  EXPECT_LT(js["planners"].size(), j["planners"].size());
  for (const auto& p : js["planners"]) {
    const auto& w = p["worlds"];
    EXPECT_NE(std::find(w.begin(), w.end(), "sim"), w.end()) << p.dump();
  }
  expect_bad_input("planners --world nosuch", "--world");
}

// A result that cannot be written after the run is a run failure: exit 1, one line naming the
// file, the previous file untouched and no temporary left. A file-size limit (ulimit -f, with
// SIGXFSZ ignored so that the write fails with EFBIG) stands in for a full disk.
TEST(Cli, AnOutputThatCannotBeWrittenIsExitOne) {
  const auto dir = std::filesystem::temp_directory_path() / "hpcplan_cli_full";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto file = dir / "result.json";
  const std::string args =
      "grid --dims 2 --extent 2000 --algo bfs --path --json --output " + file.string();
  { std::ofstream(file) << "previous\n"; }
  const CliRun r = run(args, "trap '' XFSZ; ulimit -f 8;");  // 4-8 KiB: the path is larger
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("cannot write '" + file.string() + "'"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(file), "previous\n");
  std::size_t entries = 0;
  for ([[maybe_unused]] auto& e : std::filesystem::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 1u);
  std::filesystem::remove_all(dir);
}

// Every numeric option of every subcommand, tried with what must be refused: negative values
// (none of these options takes one), NaN, infinities, overflow, words and a value past its range.
// A real option's bounds are its own: the lowest value it admits is accepted as written, though
// the long double the text reads as lies below the double the bound is (0.001 was refused).
TEST(Cli, ARealOptionsBoundIsInItsRange) {
  const CliRun at = run("sim --particles 100 --settle-frames 0 --max-sim-s 0.001 --json");
  EXPECT_EQ(at.code, 0) << at.err;
  const CliRun below = run("sim --particles 100 --settle-frames 0 --max-sim-s 0.000999");
  EXPECT_EQ(below.code, 2);
  EXPECT_NE(below.err.find("'0.000999' is out of range [0.001, 1e+09]"), std::string::npos)
      << below.err;
  const CliRun tiny = run("sim --particles 100 --settle-frames 0 --occupancy density "
                          "--density-support 0.000001 --max-sim-s 0.02");
  EXPECT_EQ(tiny.code, 0) << tiny.err;
}

TEST(Cli, EveryNumericOptionRefusesBadValues) {
  const std::string map = std::string(" --map ") + HPCPLAN_MAPS_DIR + "/single_box.txt";
  const std::string sphere = std::string(" --map ") + HPCPLAN_MAPS_DIR + "/sphere_world.txt";
  struct Case {
    std::string base, option, too_big;  // too_big: "" when the type's own range is the limit
  };
  const std::vector<Case> cases = {
      {"grid", "--dims", "17"},
      {"grid --dims 2", "--weight", "1e10"},
      {"grid --dims 2", "--seed", "18446744073709551616"},
      {"grid --dims 2", "--extent", "65536"},
      {"grid --dims 2", "--max-states", "18446744073709551616"},
      {"grid --dims 2", "--time-limit", "1e10"},
      {"grid --dims 2", "--threshold", "50"},
      {"grid --dims 2", "--density", "1.5"},
      {"grid --dims 2", "--gog-shift-p", "64"},
      {"grid --dims 2", "--gog-shift-v", "62"},
      {"grid --dims 2", "--owner-coarsen", "17"},
      {"grid --dims 2", "--owner-slabs", "1073741825"},
      {"grid --dims 2", "--owner-cuts", "4294967296"},
      {"grid --dims 2", "--batch", "1048577"},
      {"grid --dims 2", "--batch-age-ms", "1001"},
      {"grid --dims 2", "--sync-every", "1e19"},
      {"grid --dims 2", "--sent-filter", "29"},
      {"grid --dims 2", "--simulate-ranks", "1048577"},
      {"grid --dims 2 --simulate-ranks 2", "--simulate-coarsen", "17"},
      {"grid --dims 2 --algo bfs", "--threads", "4097"},
      {"grid --dims 2 --algo bfs", "--memory-budget", "18446744073709551616"},
      {"grid --dims 2 --algo bfs", "--slab-layers", "65536"},
      {"grid --dims 2 --algo bfs --checkpoint ck", "--checkpoint-every", "1e10"},
      {"ompl", "--dims", "11"},
      {"ompl --dims 2", "--time", "3601"},
      {"ompl --dims 2", "--runs", "10001"},
      {"ompl --dims 2", "--warmup", "101"},
      {"ompl --dims 2", "--seed", "18446744073709551616"},
      {"ompl --dims 2", "--extent", "1001"},
      {"ompl --dims 2", "--density", "2"},
      {"ompl --dims 2", "--resolution", "1.5"},
      {"ompl --dims 2", "--grid-weight", "1e10"},
      {"sim", "--particles", "200000001"},
      {"sim", "--runs", "1000001"},
      {"sim", "--replan-every", "1000001"},
      {"sim", "--max-sim-s", "1e10"},
      {"sim", "--max-wall-s", "1e10"},
      {"sim", "--iterations", "1e10"},
      {"sim", "--goal-bias", "1.5"},
      {"sim", "--escape", "101"},
      {"sim", "--threads", "4097"},
      {"sim", "--seed", "18446744073709551616"},
      {"sim", "--robot-radius", "1e4"},
      {"sim", "--reactive-horizon", "1e4"},
      {"sim", "--reactive-margin", "1e4"},
      {"sim", "--lockstep-delay", "1000001"},
      {"sim", "--settle-frames", "1000001"},
      {"sim", "--density-support", "1e10"},
      {"sim", "--density-threshold", "1e10"},
      {"sim", "--every", "100000001"},
      {"sim", "--memory-mb", "1e10"},
      {"sim", "--step", "1e10"},
      {"sim", "--rewire-radius", "1e10"},
      {"sim", "--goal-radius", "1e10"},
      {"sim", "--time", "1e10"},
      {"sph", "--particles", "200000001"},
      {"sph", "--frames", "100000001"},
      {"sph", "--seed", "18446744073709551616"},
      {"sph", "--threads", "4097"},
      {"sph", "--every", "100000001"},
      {"sph", "--memory-mb", "1e10"},
      {"sph", "--checkpoint-every", "100000001"},
  };
  std::vector<Case> all = cases;
  for (const char* world : {"map3d", "sphere2d"})
    for (const char* option : {"--resolution", "--spacing", "--weight", "--seed", "--time",
                               "--step", "--samples", "--max-states"}) {
      const std::string base = std::string(world) + (world[0] == 'm' ? map : sphere);
      const std::string o = option;
      all.push_back({base, o,
                     o == "--samples"                       ? "1000001"
                     : o == "--seed" || o == "--max-states" ? "18446744073709551616"
                                                            : "1e10"});
    }
  int tried = 0, expected = 0;
  for (const Case& c : all) {
    expected += c.too_big.empty() ? 10 : 11;
    std::vector<std::string> bad = {"-5",   "-0.5",  "nan", "NaN", "inf",
                                    "-inf", "1e400", "abc", "3x",  ""};
    if (!c.too_big.empty()) bad.push_back(c.too_big);
    for (const std::string& v : bad) {
      const std::string args = c.base + " " + c.option + " '" + v + "'";
      SCOPED_TRACE(args);
      const CliRun r = run(args);
      EXPECT_EQ(r.code, 2) << r.err;
      EXPECT_TRUE(r.out.empty());
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      EXPECT_NE(r.err.find(c.option), std::string::npos) << r.err;
      ++tried;
    }
  }
  EXPECT_EQ(tried, expected);
  EXPECT_EQ(all.size(), 78u);  // every numeric option of grid, ompl, sim, sph, map3d, sphere2d
}

}  // namespace
