#pragma once
// The engines' side of dense_checkpoint.hpp: what a checkpoint must have been written for,
// the file around an engine's payload, a restart every rank agrees on, and when to write.
#include <string>

#include "engine_common.hpp"
#include "hpcplan/core/checkpoint_file.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/dense/dense_checkpoint.hpp"

namespace hpcplan::dense::detail {

// The problem and layout a checkpoint is valid for, one "name = value" line each.
std::string run_identity(const ObstacleSource& field, const Query& q, const SlabMap& slabs);

// Writes `payload` after `identity` into `path` atomically (RunError naming the file if it
// cannot be written).
void write_checkpoint(const std::string& path, const std::string& identity,
                      const std::string& payload);

// A checkpoint file's bytes (InputError if it is not a readable file of this kind).
std::string read_checkpoint_file(const std::string& path);
// The engine's payload within a file's `bytes` (read from `name`), after the envelope's checks
// and the identity's: InputError "--restart 'NAME': ..." naming the first line that differs.
std::string_view open_checkpoint(std::string_view bytes, const std::string& name,
                                 const std::string& identity);

// Runs `restore` (this rank's read of its checkpoint, returning the boundary it was written
// at: levels or buckets done) on every rank. A refusal on one rank must not leave the others
// waiting in the search's first exchange: if any rank's throws an InputError, every rank
// throws one with the lowest such rank's message. The ranks' files must also be of one
// boundary (a job killed while its ranks were writing leaves some at the one before).
// Collective.
template <class Restore>
void agree_on_restart(SlabTransport& tr, Restore&& restore) {
  std::string message;
  std::uint64_t boundary = 0;
  try {
    boundary = restore();
  } catch (const InputError& e) {
    message = e.what();
    if (message.empty()) message = "--restart: refused";
  }
  const std::byte refused{static_cast<unsigned char>(message.empty() ? 0 : 1)};
  const std::vector<std::byte> flags = tr.allgather(std::span<const std::byte>(&refused, 1));
  int first = -1;
  for (std::size_t r = 0; r < flags.size() && first < 0; ++r)
    if (flags[r] != std::byte{0}) first = static_cast<int>(r);
  if (first < 0) {
    std::uint64_t span[2] = {boundary, ~boundary};  // the largest, and the smallest (negated)
    tr.max(span);
    if (span[0] != ~span[1])
      throw InputError("--restart: the ranks' checkpoints were written at different boundaries (" +
                       std::to_string(~span[1]) + " and " + std::to_string(span[0]) +
                       "): the job was stopped while writing them; start afresh");
    return;
  }
  const std::string_view mine = first == tr.rank() ? std::string_view(message) : "";
  const std::vector<std::byte> text = tr.allgather(std::as_bytes(std::span(mine)));
  std::string what(reinterpret_cast<const char*>(text.data()), text.size());
  if (tr.ranks() > 1) what = "rank " + std::to_string(first) + ": " + what;
  throw InputError(what);
}

// When the master thread asks for a checkpoint at a boundary: none, one (every_s has passed
// since the last), or one and the end (interrupted).
inline constexpr int kSave = 1, kSaveAndEnd = 2;
class CheckpointSchedule {
 public:
  explicit CheckpointSchedule(const Checkpointing& c) : c_(c) {}
  int due() {
    if (c_.path.empty()) return 0;
    if (c_.interrupted && c_.interrupted()) return kSaveAndEnd;
    if (c_.every_s > 0 && clock_.seconds() >= last_ + c_.every_s) {
      last_ = clock_.seconds();
      return kSave;
    }
    return 0;
  }

 private:
  const Checkpointing& c_;
  Stopwatch clock_;
  double last_ = 0.0;
};

}  // namespace hpcplan::dense::detail
