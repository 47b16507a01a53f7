#pragma once
// The lattice's moves on whole tiles: given the frontier bits f of one tile, every legal move
// out of those states at once, as words of target bits. A move is legal when every corner of
// the unit cube it spans is free (the seed rule: a one-axis step, or a two-axis step whose two
// one-axis intermediates are free; full connectivity: any set of axes, d <= 4). In the source
// tile's frame each corner's freeness is one window mask (free_windows.hpp), so
//     legal = f & mask(corner 1) & ... & mask(target),
// and the targets are `legal` shifted by the move: along an in-tile axis the bits split into
// the part that stays in the tile and the part that crosses into the neighbour tile, along a
// word axis they move to the neighbour tile unchanged.
//
// out(delta, bits, axes) receives each target tile (tile index + delta) once per source tile
// and move length (axes = 1: cost 1; 2: sqrt 2; ...), with the OR of the targets; nothing for
// empty words. expand() returns the number of legal moves (generated successors, the edges
// examined). The target bits are not masked by "visited": that is the caller's store.
//
// SeedMoves is the seed rule written out for the compiler (D and the tile shape fixed, every
// loop over axes unrolled); TableMoves takes any rule from a table of moves built at run time
// (full connectivity, and a second implementation of the seed rule for the tests).
//
// Threads: stateless functions / an immutable table.
#include <bit>
#include <cstdint>
#include <vector>

#include "hpcplan/dense/free_windows.hpp"

namespace hpcplan::dense {

// Shifts of source bits to target bits along in-tile axis 0 or 1, in the tile (in) and into
// the neighbour tile (out). K = 2: 8 x 8 tiles (bit x0 + 8 x1); K = 1: rows of 64 on axis 0.
template <int K>
struct InTileShift {
  static constexpr Word in(int axis, int sign, Word x) {
    if constexpr (K == 1) {
      return sign > 0 ? x << 1 : x >> 1;
    } else {
      if (axis == 0) return sign > 0 ? (x & ~kColumn7) << 1 : (x & ~kColumn0) >> 1;
      return sign > 0 ? x << 8 : x >> 8;
    }
  }
  static constexpr Word out(int axis, int sign, Word x) {
    if constexpr (K == 1) {
      return sign > 0 ? x >> 63 : x << 63;
    } else {
      if (axis == 0) return sign > 0 ? (x & kColumn7) >> 7 : (x & kColumn0) << 7;
      return sign > 0 ? x >> 56 : x << 56;
    }
  }
};

// The window of an in-tile offset along one in-tile axis (the other in-tile offset 0).
constexpr int axis_window(int axis, int sign) {
  return axis == 0 ? FreeWindows::window(sign, 0) : FreeWindows::window(0, sign);
}

template <int D, int K>
struct SeedMoves {
  static_assert(K == 1 || K == 2, "one or two in-tile axes");
  static_assert(D >= K, "in-tile axes are lattice axes");
  using Shift = InTileShift<K>;

  // kSplit: report one-axis and two-axis targets separately (Dijkstra); otherwise their OR
  // comes as axes = 1 (BFS, where every move is one level).
  template <bool kSplit, class Out>
  [[gnu::always_inline]] static inline std::uint64_t expand(Word f, const FreeWindows::At& at,
                                                            int stride, const std::int64_t* W,
                                                            Out&& out) {
    const int tau = at.tau;
    // The nine windows' rows of this tile, so a mask is one indexed load.
    const Word* win[FreeWindows::kWindows];
    for (int w = 0; w < FreeWindows::kWindows; ++w) win[w] = at.row + w * stride;
    auto P = [&win](int w, int t) { return win[w][t]; };
    constexpr int kDiag = kSplit ? 2 : 1;
    std::uint64_t gen = 0;
    // Source-frame masks of the one-step neighbours along the in-tile axes.
    Word pin[2][2] = {};
    for (int a = 0; a < K; ++a)
      for (int s = 0; s < 2; ++s) pin[a][s] = P(axis_window(a, s ? 1 : -1), tau);
    // Target words: the tile itself and its face neighbours, one-axis (u) and two-axis (d).
    Word self_u = 0, self_d_split = 0;
    Word face_u[D][2] = {}, face_d_split[D][2] = {};
    Word& self_d = kSplit ? self_d_split : self_u;
    Word(&face_d)[D][2] = kSplit ? face_d_split : face_u;
    // One-axis moves inside the tile's axes.
#pragma GCC unroll 2
    for (int a = 0; a < K; ++a)
#pragma GCC unroll 2
      for (int s = 0; s < 2; ++s) {
        const int sg = s ? 1 : -1;
        const Word m = f & pin[a][s];
        gen += std::popcount(m);
        self_u |= Shift::in(a, sg, m);
        face_u[a][s] |= Shift::out(a, sg, m);
      }
    // Two-axis moves inside the tile's axes (8 x 8 tiles: axes 0 and 1).
    if constexpr (K == 2) {
#pragma GCC unroll 2
      for (int s0 = 0; s0 < 2; ++s0)
#pragma GCC unroll 2
        for (int s1 = 0; s1 < 2; ++s1) {
          const int g0 = s0 ? 1 : -1, g1 = s1 ? 1 : -1;
          const Word m = f & pin[0][s0] & pin[1][s1] & P(FreeWindows::window(g0, g1), tau);
          if (!m) continue;
          gen += std::popcount(m);
          const Word i0 = Shift::in(0, g0, m), x0 = Shift::out(0, g0, m);
          self_d |= Shift::in(1, g1, i0);
          face_d[1][s1] |= Shift::out(1, g1, i0);
          face_d[0][s0] |= Shift::in(1, g1, x0);
          if (const Word c = Shift::out(1, g1, x0)) out(g0 * W[0] + g1 * W[1], c, kDiag);
        }
    }
    // Word axes: the neighbour tile's own mask (same bits), tau moved by the level change.
    int tw[D][2];
    Word pw[D][2];
#pragma GCC unroll 16
    for (int b = K; b < D; ++b) {
      tw[b][0] = tau + at.minus[b];
      tw[b][1] = tau + at.plus[b];
      pw[b][0] = P(FreeWindows::window(0, 0), tw[b][0]);
      pw[b][1] = P(FreeWindows::window(0, 0), tw[b][1]);
    }
#pragma GCC unroll 16
    for (int b = K; b < D; ++b)
#pragma GCC unroll 2
      for (int sb = 0; sb < 2; ++sb) {
        const int gb = sb ? 1 : -1;
        const Word m = f & pw[b][sb];
        if (!m) continue;
        gen += std::popcount(m);
        face_u[b][sb] |= m;
        const int tb = tw[b][sb];
        const std::int64_t db = gb * W[b];
        // With an in-tile axis: the corner x + e_a is the in-tile neighbour, x + e_b the word
        // neighbour, the target the in-tile window of the word neighbour.
#pragma GCC unroll 2
        for (int a = 0; a < K; ++a)
#pragma GCC unroll 2
          for (int sa = 0; sa < 2; ++sa) {
            const int ga = sa ? 1 : -1;
            const Word q = m & pin[a][sa] & P(axis_window(a, ga), tb);
            if (!q) continue;
            gen += std::popcount(q);
            face_d[b][sb] |= Shift::in(a, ga, q);
            if (const Word c = Shift::out(a, ga, q)) out(db + ga * W[a], c, kDiag);
          }
          // With a later word axis: both neighbours and the target are whole tiles.
#pragma GCC unroll 16
        for (int c = b + 1; c < D; ++c)
#pragma GCC unroll 2
          for (int sc = 0; sc < 2; ++sc) {
            const int tc = tb + (sc ? at.plus[c] : at.minus[c]);
            const Word q = m & pw[c][sc] & P(FreeWindows::window(0, 0), tc);
            if (!q) continue;
            gen += std::popcount(q);
            out(db + (sc ? W[c] : -W[c]), q, kDiag);
          }
      }
    if (self_u) out(0, self_u, 1);
    if constexpr (kSplit)
      if (self_d) out(0, self_d, 2);
#pragma GCC unroll 16
    for (int a = 0; a < D; ++a) {
      if (face_u[a][0]) out(-W[a], face_u[a][0], 1);
      if (face_u[a][1]) out(W[a], face_u[a][1], 1);
      if constexpr (kSplit) {
        if (face_d[a][0]) out(-W[a], face_d[a][0], 2);
        if (face_d[a][1]) out(W[a], face_d[a][1], 2);
      }
    }
    return gen;
  }
};

// Any rule, from a table: each move lists its corners (window and word-axis steps) and the
// in-tile axes whose shift splits its targets. Used for full connectivity (3^d - 1 moves,
// d <= 4) and, with max_axes = 2, as the tests' second implementation of the seed rule.
class TableMoves {
 public:
  TableMoves(const TileLayout& layout, int max_axes);
  std::size_t moves() const { return moves_.size(); }

  template <int K, bool kSplit, class Out>
  std::uint64_t expand(Word f, const FreeWindows::At& at, int stride, const std::int64_t* W,
                       Out&& out) const {
    using Shift = InTileShift<K>;
    std::uint64_t gen = 0;
    for (const Move& mv : moves_) {
      Word m = f;
      for (const Corner& c : mv.corners) {
        int t = at.tau;
        for (int j = 0; j < c.word_steps; ++j)
          t += c.word_sign[j] > 0 ? at.plus[c.word_axis[j]] : at.minus[c.word_axis[j]];
        m &= at.row[c.window * stride + t];
        if (!m) break;
      }
      if (!m) continue;
      gen += std::popcount(m);
      std::int64_t base = 0;
      for (int j = 0; j < mv.word_steps; ++j) base += mv.word_sign[j] * W[mv.word_axis[j]];
      const int kind = kSplit ? mv.axes : 1;
      // Split the targets along each in-tile axis of the move: 2^(in-tile axes) parts.
      Word part[4] = {m, 0, 0, 0};
      std::int64_t delta[4] = {base, 0, 0, 0};
      int parts = 1;
      for (int j = 0; j < mv.in_steps; ++j) {
        const int a = mv.in_axis[j], g = mv.in_sign[j];
        for (int p = 0; p < parts; ++p) {
          part[parts + p] = Shift::out(a, g, part[p]);
          delta[parts + p] = delta[p] + g * W[a];
          part[p] = Shift::in(a, g, part[p]);
        }
        parts *= 2;
      }
      for (int p = 0; p < parts; ++p)
        if (part[p]) out(delta[p], part[p], kind);
    }
    return gen;
  }

 private:
  struct Corner {
    int window = FreeWindows::window(0, 0);
    int word_steps = 0;
    int word_axis[kMaxDims] = {};
    int word_sign[kMaxDims] = {};
  };
  struct Move {
    int axes = 0;
    int in_steps = 0;
    int in_axis[2] = {};
    int in_sign[2] = {};
    int word_steps = 0;
    int word_axis[kMaxDims] = {};
    int word_sign[kMaxDims] = {};
    std::vector<Corner> corners;  // every corner but the source, the target last
  };
  std::vector<Move> moves_;
};

}  // namespace hpcplan::dense
