#pragma once
// A result table: named columns and rows of typed cells. The simulator's per-run and
// per-replan rows are built once as a Table; the CSV files are its text (to_csv), and the
// Python module hands the same rows to Python as typed values, so the two cannot disagree on a
// column's name, order or meaning.
#include <cstdint>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace hpcplan::io {

// An empty cell (a timing left out for byte-identical lockstep files, a time to goal of a run
// that failed), a whole number (signed, or unsigned for seeds and counts of 64 bits), a real
// number or text.
using Cell = std::variant<std::monostate, std::int64_t, std::uint64_t, double, std::string>;

// A whole number as its cell: unsigned types as std::uint64_t, signed ones (and bool) as
// std::int64_t.
template <class T>
Cell whole(T v) {
  if constexpr (std::is_unsigned_v<T> && !std::is_same_v<T, bool>)
    return Cell(static_cast<std::uint64_t>(v));
  else
    return Cell(static_cast<std::int64_t>(v));
}

struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<Cell>> rows;
};

// The header line (when asked) and one line per row: integers in full, reals with 6
// significant digits (%.6g), text as it is, an empty cell as nothing.
std::string to_csv(const Table& table, bool header = true);

}  // namespace hpcplan::io
