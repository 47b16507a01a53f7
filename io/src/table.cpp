#include "hpcplan/io/table.hpp"

#include <cstdio>
#include <type_traits>

namespace hpcplan::io {

namespace {

std::string text(const Cell& cell) {
  return std::visit(
      [](const auto& v) -> std::string {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>) {
          return {};
        } else if constexpr (std::is_integral_v<T>) {
          return std::to_string(v);
        } else if constexpr (std::is_same_v<T, double>) {
          char buf[64];
          std::snprintf(buf, sizeof buf, "%.6g", v);
          return buf;
        } else {
          return v;
        }
      },
      cell);
}

}  // namespace

std::string to_csv(const Table& table, bool header) {
  std::string out;
  if (header) {
    for (std::size_t k = 0; k < table.columns.size(); ++k) {
      if (k > 0) out += ',';
      out += table.columns[k];
    }
    out += '\n';
  }
  for (const std::vector<Cell>& row : table.rows) {
    for (std::size_t k = 0; k < row.size(); ++k) {
      if (k > 0) out += ',';
      out += text(row[k]);
    }
    out += '\n';
  }
  return out;
}

}  // namespace hpcplan::io
