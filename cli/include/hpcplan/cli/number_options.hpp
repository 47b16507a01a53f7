#pragma once
// Numeric options that refuse, with exit 2 and one line, what a plain CLI11 option lets through:
// a negative value for an unsigned target (CLI11 wraps "-5" to 2^64 - 5), NaN and infinities,
// an integer with a leading zero (CLI11 reads "010" as octal 8), and anything outside the
// option's range. Every numeric option of every subcommand is added through add_number, so one
// table-driven test covers them all (tests/cli/test_cli.cpp).
#include <CLI/CLI.hpp>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "hpcplan/plan/planner_registry.hpp"

namespace hpcplan::cli {

// The validator's description, shown in --help after the type and read by the Python module's
// signatures, is the range when the option has one of its own ("[2, 65535]"), else "NUMBER".
template <class T>
CLI::Validator number_check(long double lo, long double hi, bool show_range = true) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        const char* begin = text.c_str();
        char* end = nullptr;
        errno = 0;
        const long double v = std::strtold(begin, &end);
        if (end == begin || *end != '\0') return "'" + text + "' is not a number";
        if (!std::isfinite(v) || errno == ERANGE) return "'" + text + "' is not a finite number";
        if constexpr (std::is_integral_v<T>) {
          if (v != std::floor(v)) return "'" + text + "' is not a whole number";
          // CLI11 reads an integer as C does (strtoll, base 0): "010" would be 8, not the 10
          // checked here, so a leading zero is refused rather than misread.
          const char* digits = begin + std::strspn(begin, " \t\n\v\f\r");
          if (*digits == '+' || *digits == '-') ++digits;
          if (digits[0] == '0' && std::isdigit(static_cast<unsigned char>(digits[1])))
            return "'" + text + "' has a leading zero (which would make it octal)";
        }
        // A real option compares the value it will hold (the text read as T) with its bounds
        // as T holds them: "1e-9" against a bound of 1e-9 is in range, although the long
        // double 1e-9 is below the double nearest to it.
        const long double held =
            std::is_floating_point_v<T> ? static_cast<long double>(static_cast<T>(v)) : v;
        if (held < lo || held > hi)
          return "'" + text + "' is out of range [" + CLI::detail::to_string(static_cast<T>(lo)) +
                 ", " + CLI::detail::to_string(static_cast<T>(hi)) + "]";
        return {};
      },
      show_range ? "[" + CLI::detail::to_string(static_cast<T>(lo)) + ", " +
                       CLI::detail::to_string(static_cast<T>(hi)) + "]"
                 : std::string("NUMBER"),
      "number");
}

template <class T>
struct NumberOf {
  using type = T;
};
template <class T>
struct NumberOf<std::vector<T>> {  // a delimited list: each element is checked
  using type = T;
};

// An option whose values must lie in [lo, hi] (and within the target type).
template <class Target>
CLI::Option* add_number(CLI::App* cmd, const std::string& name, Target& target,
                        const std::string& help, long double lo, long double hi,
                        bool show_range = true) {
  using T = typename NumberOf<Target>::type;
  static_assert(std::is_arithmetic_v<T>);
  lo = std::max<long double>(lo, std::numeric_limits<T>::lowest());
  hi = std::min<long double>(hi, std::numeric_limits<T>::max());
  return cmd->add_option(name, target, help)->check(number_check<T>(lo, hi, show_range));
}

// Any value of the target's type (no negative one for an unsigned type, nothing non-finite).
template <class Target>
CLI::Option* add_number(CLI::App* cmd, const std::string& name, Target& target,
                        const std::string& help) {
  using T = typename NumberOf<Target>::type;
  return add_number(cmd, name, target, help, std::numeric_limits<T>::lowest(),
                    std::numeric_limits<T>::max(), false);
}

// An option the planner registry declares: its name, range and help come from there, so the
// CLI, `hpcplan planners` and the errors agree.
template <class Target>
CLI::Option* add_param(CLI::App* cmd, std::string_view name, Target& target) {
  const plan::ParamSpec& p = plan::PlannerRegistry::get().param(name);
  if constexpr (std::is_same_v<Target, bool>) {
    return cmd->add_flag(p.option(), target, p.help);
  } else if constexpr (std::is_same_v<Target, std::string>) {
    return cmd->add_option(p.option(), target, p.help)->check(CLI::IsMember(p.choices));
  } else {
    return add_number(cmd, p.option(), target, p.help, p.lo, p.hi);
  }
}

// "a|b|c" of a setting's planners, for --algo's help.
inline std::string planner_names(std::string_view world) {
  std::string s;
  for (const std::string& n : plan::PlannerRegistry::get().names(world))
    s += (s.empty() ? "" : "|") + n;
  return s;
}

}  // namespace hpcplan::cli
