#pragma once
// A subcommand's options described for a front end that is not a command line: the Python
// module builds its keyword arguments, signatures and docstrings from this, read from the
// CLI11 command itself, so that names, types, defaults, ranges and help are the ones
// `hpcplan <command> --help` shows and the registry declares, and cannot drift apart.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace hpcplan::cli {

struct OptionInfo {
  std::string name;    // the keyword: the long name with - as _ ("max_states")
  std::string option;  // "--max-states"
  // flag | int | float | text | int_list | float_list (a delimited list of numbers)
  std::string kind;
  std::string default_text;  // what --help shows after '='; empty: no default of its own
  bool required = false;
  std::string range;                 // "[2, 65535]" (numbers with a range of their own)
  std::vector<std::string> choices;  // a fixed set of values ({auto,dense,sparse})
  std::string help;
  std::string group;
};

// Every option of `command` but --help, in the order --help lists them.
std::vector<OptionInfo> describe_options(const CLI::App& command);

}  // namespace hpcplan::cli
