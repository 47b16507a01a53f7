// hpcplan: one executable, one subcommand per planning setting.
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "commands.hpp"
#include "hpcplan/core/error.hpp"

namespace {

// Error messages are promised to be one line.
std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

int report(int code, const std::string& message) {
  std::fprintf(stderr, "hpcplan: error: %s\n", one_line(message).c_str());
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"hpcplan: HPC motion planning on implicit grids, sampling planners and fluids"};
  app.require_subcommand(1);
  hpcplan::cli::Action grid = hpcplan::cli::register_grid_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    return report(hpcplan::kExitBadInput, e.what());
  }
  try {
    if (app.got_subcommand("grid")) return grid();
    return report(hpcplan::kExitBadInput, "no subcommand given");
  } catch (const hpcplan::InputError& e) {
    return report(hpcplan::kExitBadInput, e.what());
  } catch (const hpcplan::RunError& e) {
    return report(hpcplan::kExitRunFailure, e.what());
  } catch (const std::bad_alloc&) {
    return report(hpcplan::kExitRunFailure,
                  "out of memory; lower --max-states or the problem size");
  } catch (const std::exception& e) {
    return report(hpcplan::kExitRunFailure, e.what());
  }
}
