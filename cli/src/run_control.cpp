#include "hpcplan/cli/run_control.hpp"

#include "hpcplan/core/interrupt.hpp"

namespace hpcplan::cli {

std::string RunControl::stopped_by() const {
  if (const char* name = interruption ? interruption() : nullptr) return name;
  return "stop requested";
}

RunControl signal_control() {
  interrupt::install();
  RunControl control;
  control.interruption = []() -> const char* {
    const int signal = interrupt::requested();
    return signal != 0 ? interrupt::name(signal) : nullptr;
  };
  return control;
}

}  // namespace hpcplan::cli
