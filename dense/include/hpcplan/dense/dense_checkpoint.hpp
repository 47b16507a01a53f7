#pragma once
// Checkpoints of the dense engine (hpcplan grid --checkpoint / --restart): a run stops at a
// level (BFS) or bucket (Dijkstra) boundary and a later run continues from there with the same
// answer (status, cost, hops, path, expansions and every other counter; timings and the
// figures of list memory aside).
//
// What is saved, one file per rank, and why it suffices: at a boundary every thread has
// finished the level or bucket, applied what the other threads and ranks sent it, and holds
// nothing in its outboxes, so a rank's whole state is
//   BFS: its slab's 2-bit codes (reached, level mod 3), each thread's frontier (the tiles
//     reached in the level just finished, with the bits they had before it), the level, the
//     states reached and the largest level so far;
//   Dijkstra: its slab's settled bits (and each state's class with --path), each thread's
//     pending classes and their lists, the classes it settled (for the class count), the
//     bucket, the buckets processed and the largest pending count;
//   both: each thread's expansion and generation counts, and the peak of its list memory.
// The field, the window table and the slab plan are rebuilt from the problem. A checkpoint is
// only valid for the same problem (field, start, goal, algorithm, connectivity; Dijkstra's
// --path) and the same layout (ranks, this rank's number, threads, layers per block): each
// names them, and a restart that differs in any is refused with a line naming the first.
//
// Thread safety: the engine calls `interrupted` on the master thread of each rank, once per
// level or bucket.
#include <functional>
#include <string>

namespace hpcplan::dense {

struct Checkpointing {
  std::string path;      // this rank's file to write at boundaries; empty: none
  double every_s = 0.0;  // > 0: write one every this many seconds of search
  // Asked at every boundary; true on any rank: every rank writes its checkpoint there and the
  // run ends with Status::interrupted. Only with a path.
  std::function<bool()> interrupted;
  std::string restart;  // this rank's file to continue from; empty: start afresh
};

// The file of `rank` of `ranks` for the user's FILE: FILE itself on one rank, FILE.r<rank>
// on several.
std::string rank_file(const std::string& file, int rank, int ranks);

}  // namespace hpcplan::dense
