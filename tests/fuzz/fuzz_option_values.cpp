// libFuzzer target for the CLI's option values: the numeric options (cli/number_options.hpp's
// add_number, through which every numeric option of every subcommand is added: here one of each
// value type the CLI uses, with ranges it uses), the grid's lattice states (hpcplan grid
// --start/--goal: parse_coordinates) and the continuous worlds' points (hpcplan map3d and
// sphere2d --start/--goal: cli/point_option.hpp). Any string must either give the value it
// names, within the option's range, or be refused with a message: CLI11's ValidationError or
// ConversionError for the numeric options (exit 2 and that line in the CLI), an InputError for
// the others. Anything else is a bug: another exception, a crash, a sanitizer report, or a
// value accepted that is not the number the text names or lies outside the range.
//
// The input is one option value as a shell passes it (up to its first NUL byte), tried on
// every option.
#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>

#include "hpcplan/cli/number_options.hpp"
#include "hpcplan/cli/point_option.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/plan/grid_problem.hpp"

namespace {

void check(bool ok) {
  if (!ok) std::abort();
}

// The number `text` names in full, as the CLI documents its numbers (strtold), or NaN.
long double named(const std::string& text) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const long double v = std::strtold(begin, &end);
  return end == begin || *end != '\0' ? NAN : v;
}

// An option added with add_number(lo, hi), parsed from `--value=TEXT`: on success the value
// must lie in [lo, hi] and be the number the text names. (One app per option, made once and
// parsed again for every input, as CLI11 allows: fresh apps ran 2,300 inputs/s, these 5,500.)
template <class T>
struct Scalar {
  Scalar(long double lo, long double hi) : lo(lo), hi(hi) {
    hpcplan::cli::add_number(&app, "--value", value, "", lo, hi);
  }
  void parse(const std::string& text) {
    value = T{};
    try {
      app.parse(std::vector<std::string>{"--value=" + text});
    } catch (const CLI::ParseError& e) {
      check(e.what()[0] != '\0');
      return;
    }
    check(static_cast<long double>(value) >= lo && static_cast<long double>(value) <= hi);
    const long double v = named(text);
    if constexpr (std::is_integral_v<T>)
      check(v == static_cast<long double>(value));
    else
      check(static_cast<T>(v) == value);
  }
  long double lo, hi;
  CLI::App app;
  T value{};
};

// The same for a comma-delimited list: every element in [lo, hi].
template <class T>
struct List {
  List(long double lo, long double hi) : lo(lo), hi(hi) {
    hpcplan::cli::add_number(&app, "--values", values, "", lo, hi)->delimiter(',');
  }
  void parse(const std::string& text) {
    values.clear();
    try {
      app.parse(std::vector<std::string>{"--values=" + text});
    } catch (const CLI::ParseError& e) {
      check(e.what()[0] != '\0');
      return;
    }
    for (const T v : values)
      check(static_cast<long double>(v) >= lo && static_cast<long double>(v) <= hi);
  }
  long double lo, hi;
  CLI::App app;
  std::vector<T> values;
};

// The comma-separated items of `text`, empty ones included.
std::vector<std::string> items(const std::string& text) {
  std::vector<std::string> out;
  for (std::size_t at = 0;;) {
    const std::size_t comma = text.find(',', at);
    out.push_back(text.substr(at, comma == std::string::npos ? comma : comma - at));
    if (comma == std::string::npos) return out;
    at = comma + 1;
  }
}

// On success: one integer per item, each the one the item names.
void lattice_state(const std::string& text) {
  try {
    const std::vector<int> c = hpcplan::parse_coordinates(text, "--start");
    const std::vector<std::string> item = items(text);
    check(c.size() == item.size());
    for (std::size_t k = 0; k < c.size(); ++k) check(named(item[k]) == c[k]);
  } catch (const hpcplan::InputError& e) {
    check(e.what()[0] != '\0');
  }
}

// On success: exactly D items, each the finite number it names.
template <int D>
void point(const std::string& text) {
  try {
    const hpcplan::env::Vec<D> p = hpcplan::cli::parse_point<D>(text, "--start");
    const std::vector<std::string> item = items(text);
    check(item.size() == D);
    for (int k = 0; k < D; ++k) {
      char* end = nullptr;
      const double v = std::strtod(item[k].c_str(), &end);  // (points are doubles: strtod)
      check(std::isfinite(p[k]) && end != item[k].c_str() && *end == '\0' && v == p[k]);
    }
  } catch (const hpcplan::InputError& e) {
    check(e.what()[0] != '\0');
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  text.resize(std::string_view(text).find('\0') == std::string_view::npos ? text.size()
                                                                          : text.find('\0'));
  // The value types and ranges of the CLI's numeric options.
  static Scalar<int> dims(1, 16), extent(2, 65535);   // grid --dims, --extent
  static Scalar<unsigned> particles(1, 200'000'000);  // sph --particles
  static Scalar<std::uint64_t> seed(0, std::numeric_limits<std::uint64_t>::max());  // --seed
  static Scalar<std::uint64_t> sync_every(1, 1e18);  // grid --sync-every
  static Scalar<double> density(0, 1);               // grid --density
  static Scalar<double> any(std::numeric_limits<double>::lowest(),
                            std::numeric_limits<double>::max());  // the whole type
  static List<int> ranks(1, 1048576);                             // grid --simulate-ranks
  static List<std::uint32_t> cuts(1, 4294967295.0);               // grid --owner-cuts
  dims.parse(text);
  extent.parse(text);
  particles.parse(text);
  seed.parse(text);
  sync_every.parse(text);
  density.parse(text);
  any.parse(text);
  ranks.parse(text);
  cuts.parse(text);
  lattice_state(text);
  point<2>(text);
  point<3>(text);
  return 0;
}
