#include "hpcplan/io/ompl_bench_csv.hpp"

#include <cstdio>
#include <sstream>

namespace hpcplan::io {

namespace {

std::string csv_number(double v, const char* format = "%.6f") {
  if (v < 0) return "";  // not available
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

}  // namespace

std::string ompl_bench_csv(const plan::OmplBenchResult& result) {
  std::ostringstream out;
  out << "planner,dims,run,seed,solved,time_first_s,length_first,quality_first,time_best_s,"
         "quality_best,quality_final,length_final,time_s,collision_checks,path_valid,"
         "improvements,smoothing_s\n";
  for (const auto& r : result.rows) {
    std::string trace;
    for (const auto& [t, len] : r.improvements) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%s%.6f:%.6f", trace.empty() ? "" : ";", t, len);
      trace += buf;
    }
    out << r.planner << ',' << r.dims << ',' << r.run << ',' << r.seed << ',' << (r.solved ? 1 : 0)
        << ',' << csv_number(r.time_first_s) << ',' << csv_number(r.length_first) << ','
        << csv_number(r.quality_first) << ',' << csv_number(r.time_best_s) << ','
        << csv_number(r.quality_best) << ',' << csv_number(r.quality_final) << ','
        << csv_number(r.length_final) << ',' << csv_number(r.time_s) << ',' << r.collision_checks
        << ',' << (r.path_valid ? 1 : 0) << ',' << trace << ',' << csv_number(r.smoothing_s)
        << '\n';
  }
  return out.str();
}

}  // namespace hpcplan::io
