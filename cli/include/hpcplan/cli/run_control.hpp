#pragma once
// How a subcommand's run may be ended from outside, whichever front end started it: the
// executable's signals (SIGUSR1, SIGTERM, Ctrl-C through core/interrupt.hpp), or the Python
// module's stop source and Ctrl-C. The run itself never asks where a request came from.
//
// Threads: a value copied into the run; `cancel` may be triggered and `interruption` answered
// from any thread.
#include <functional>
#include <stop_token>
#include <string>

namespace hpcplan::cli {

struct RunControl {
  // Ends a search or plan with status cancelled; ends a fluid or simulator run at its next
  // frame's end, as an interruption does.
  std::stop_token cancel;
  // Asked at a run's safe boundaries (the dense engine's levels and buckets, the frames): a
  // name ("SIGUSR1", "KeyboardInterrupt") ends the run there, with its checkpoint where one
  // was asked for (status interrupted); null lets it go on.
  std::function<const char*()> interruption;

  bool interrupted() const { return interruption && interruption() != nullptr; }
  // A frame loop's stop condition: an interruption or a cancel.
  bool should_stop() const { return interrupted() || cancel.stop_requested(); }
  // Why a run that stopped early stopped: the interruption's name, else "stop requested".
  std::string stopped_by() const;
};

// The executable's control: installs core/interrupt.hpp's handlers and reads them.
RunControl signal_control();

}  // namespace hpcplan::cli
