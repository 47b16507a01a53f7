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

// Error messages are promised to be one line (the CLI's stderr line, the Python module's
// exception): line breaks become spaces, trailing spaces go.
inline std::string one_line(std::string message) {
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  while (!message.empty() && message.back() == ' ') message.pop_back();
  return message;
}

inline constexpr int kExitOk = 0;
inline constexpr int kExitRunFailure = 1;
inline constexpr int kExitBadInput = 2;

}  // namespace hpcplan
