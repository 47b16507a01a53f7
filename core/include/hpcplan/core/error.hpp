#pragma once
// Two kinds of failure the user must be able to tell apart by exit code:
// bad input (exit 2) and a run that could not complete (exit 1).
#include <stdexcept>
#include <string>

namespace hpcplan {

// The request itself is wrong: malformed option, impossible value, start inside an obstacle.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Something failed while running a valid request (I/O, an internal invariant).
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline constexpr int kExitOk = 0;
inline constexpr int kExitRunFailure = 1;
inline constexpr int kExitBadInput = 2;

}  // namespace hpcplan
