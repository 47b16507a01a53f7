#include "hpcplan/graph/cspace_graph.hpp"

#include <algorithm>
#include <numeric>

#include "hpcplan/core/error.hpp"

namespace hpcplan {

std::string_view to_string(CSpaceMoves m) {
  return m == CSpaceMoves::axes ? "axes" : "seed_pairs";
}

CSpaceMoves parse_cspace_moves(std::string_view name) {
  if (name == "axes") return CSpaceMoves::axes;
  if (name == "seed" || name == "seed_pairs" || name == "pairs") return CSpaceMoves::seed_pairs;
  throw InputError("unknown --moves '" + std::string(name) + "' (expected axes or pairs)");
}

namespace {

KeyLayout checked_layout(const ConfigSpace& space, int cells) {
  const int d = space.dims();
  if (d > kMaxDims)
    throw InputError(space.name() + ": the lattice engines take at most " +
                     std::to_string(kMaxDims) + " axes, got " + std::to_string(d));
  bool periodic = false;
  for (const auto& a : space.axes()) periodic = periodic || a.periodic;
  const int least = periodic ? 3 : 2;
  if (cells < least || cells > kMaxExtent)
    throw InputError("--cells must be in " + std::to_string(least) + ".." +
                     std::to_string(kMaxExtent) + ", got " + std::to_string(cells));
  const KeyLayout layout(d, cells);
  if (layout.words() > CSpaceGraph::kWords)
    throw InputError("--cells " + std::to_string(cells) + " at " + std::to_string(d) +
                     " axes needs more than 128 bits per state; use fewer cells");
  return layout;
}

}  // namespace

CSpaceGraph::CSpaceGraph(const ConfigSpace& space, int cells, CSpaceMoves moves)
    : space_(space),
      dims_(space.dims()),
      cells_(cells),
      moves_kind_(moves),
      layout_(checked_layout(space, cells)) {
  for (const auto& a : space.axes()) {
    lower_.push_back(a.lower);
    upper_.push_back(a.upper);
    periodic_.push_back(a.periodic);
    step_.push_back(a.periodic ? (a.upper - a.lower) / cells : (a.upper - a.lower) / (cells - 1));
  }
  // Singles (axis, -/+), then pairs i < k (-/+, -/+).
  for (int i = 0; i < dims_; ++i)
    for (int s = -1; s <= 1; s += 2) {
      MoveDef m;
      m.axis[0] = i;
      m.step[0] = s;
      m.cost = step_[i];
      moves_.push_back(m);
    }
  if (moves == CSpaceMoves::seed_pairs)
    for (int i = 0; i < dims_; ++i)
      for (int k = i + 1; k < dims_; ++k)
        for (int si = -1; si <= 1; si += 2)
          for (int sk = -1; sk <= 1; sk += 2) {
            MoveDef m;
            m.axis[0] = i;
            m.axis[1] = k;
            m.step[0] = si;
            m.step[1] = sk;
            m.axes = 2;
            m.cost = std::hypot(step_[i], step_[k]);
            moves_.push_back(m);
          }
}

std::vector<double> CSpaceGraph::vertex(const State& s) const {
  int c[kMaxDims];
  layout_.unpack(s, c);
  std::vector<double> q(dims_);
  vertex(c, q.data());
  return q;
}

double CSpaceGraph::distance(std::span<const double> a, std::span<const double> b) const {
  double s = 0.0;
  for (int i = 0; i < dims_; ++i) {
    const double d = axis_difference(space_.axes()[i], a[i], b[i]);
    s += d * d;
  }
  return std::sqrt(s);
}

std::vector<std::vector<int>> CSpaceGraph::vertices_near(std::span<const double> q,
                                                         std::size_t limit) const {
  // Per axis the two nearest cells (the one below and the one above the value; on a bounded
  // axis's last cell, the one below it), nearest first, and what taking the second costs.
  std::vector<std::array<int, 2>> pick(dims_);
  std::vector<double> extra(dims_, 0.0);
  std::vector<double> v(dims_);
  for (int a = 0; a < dims_; ++a) {
    const double u = (q[a] - lower_[a]) / step_[a];
    int lo = static_cast<int>(std::floor(u));
    int hi = lo + 1;
    if (periodic_[a]) {
      lo = ((lo % cells_) + cells_) % cells_;
      hi = ((hi % cells_) + cells_) % cells_;
    } else {
      lo = std::clamp(lo, 0, cells_ - 1);
      hi = std::clamp(hi, 0, cells_ - 1);
      if (lo == hi) lo = hi > 0 ? hi - 1 : 1;  // on a face: the cell's other side
    }
    const double dlo = std::abs(axis_difference(space_.axes()[a], q[a], coordinate(a, lo)));
    const double dhi = std::abs(axis_difference(space_.axes()[a], q[a], coordinate(a, hi)));
    pick[a] = dlo <= dhi ? std::array<int, 2>{lo, hi} : std::array<int, 2>{hi, lo};
    extra[a] = std::abs(dlo * dlo - dhi * dhi);
  }
  // The corners of the cell in order of distance: only the axes whose second pick costs least
  // are varied (at most 10 of them, 1024 corners), so in any dimension the candidates are the
  // nearest corners, not the first ones of an axis order.
  std::vector<int> axes(dims_);
  std::iota(axes.begin(), axes.end(), 0);
  std::stable_sort(axes.begin(), axes.end(), [&](int x, int y) { return extra[x] < extra[y]; });
  const int vary = std::min(dims_, 10);
  std::vector<std::pair<double, std::vector<int>>> all;
  for (std::uint32_t mask = 0; mask < (1u << vary); ++mask) {
    std::vector<int> c(dims_);
    for (int a = 0; a < dims_; ++a) c[a] = pick[a][0];
    for (int j = 0; j < vary; ++j)
      if (mask >> j & 1) c[axes[j]] = pick[axes[j]][1];
    vertex(c.data(), v.data());
    all.emplace_back(distance(q, v), std::move(c));
  }
  std::sort(all.begin(), all.end());
  std::vector<std::vector<int>> out;
  for (auto& [d, c] : all) {
    if (std::find(out.begin(), out.end(), c) != out.end()) continue;
    out.push_back(std::move(c));
    if (out.size() == limit) break;
  }
  return out;
}

bool CSpaceGraph::step(const int* cx, const MoveDef& m, int* out) const {
  std::copy(cx, cx + dims_, out);
  for (int j = 0; j < m.axes; ++j) {
    const int a = m.axis[j];
    int v = cx[a] + m.step[j];
    if (periodic_[a]) {
      if (v < 0)
        v += cells_;
      else if (v >= cells_)
        v -= cells_;
    } else if (v < 0 || v >= cells_) {
      return false;
    }
    out[a] = v;
  }
  return true;
}

CSpaceGraph::State CSpaceGraph::predecessor(const State& t, Move m) const {
  int ct[kMaxDims], cp[kMaxDims];
  layout_.unpack(t, ct);
  MoveDef back = moves_[m];
  for (int j = 0; j < back.axes; ++j) back.step[j] = -back.step[j];
  if (!step(ct, back, cp)) throw std::logic_error("CSpaceGraph: predecessor leaves the lattice");
  return pack(std::span<const int>(cp, dims_));
}

double CSpaceGraph::checked_edge_length(const State& a, const State& b) const {
  int ca[kMaxDims], cb[kMaxDims];
  layout_.unpack(a, ca);
  layout_.unpack(b, cb);
  int moved = 0;
  for (int i = 0; i < dims_; ++i) {
    int diff = cb[i] - ca[i];
    if (periodic_[i]) {
      if (diff == cells_ - 1) diff = -1;
      if (diff == -(cells_ - 1)) diff = 1;
    }
    if (diff < -1 || diff > 1) return -1.0;
    moved += diff != 0;
  }
  if (moved == 0 || moved > (moves_kind_ == CSpaceMoves::axes ? 1 : 2)) return -1.0;
  std::vector<double> qa(dims_), qb(dims_);
  vertex(ca, qa.data());
  vertex(cb, qb.data());
  const Motion motion(space_, qa, qb);
  std::vector<double> samples;
  const std::size_t m = motion.samples(samples);
  for (std::size_t i = 0; i < m; ++i) {
    ++checks_;
    if (!space_.is_valid(samples.data() + i * dims_)) return -1.0;
  }
  return motion.length();
}

void CSpaceGraph::test(const std::vector<double>& states, std::vector<std::uint8_t>& ok) const {
  const std::size_t k = states.size() / static_cast<std::size_t>(dims_);
  ok.resize(k);
  if (k == 0) return;
  checks_ += k;
  if (!batch_checks_) {  // one state at a time: the baseline the batches are measured against
    for (std::size_t i = 0; i < k; ++i) ok[i] = space_.is_valid(states.data() + i * dims_);
    return;
  }
  space_.are_valid(states.data(), k, ok.data());
  ++batches_;
}

void CSpaceGraph::check_candidates() const {
  const std::size_t d = static_cast<std::size_t>(dims_);
  // Ends: the cache, then one batch of the unknown ones.
  batch_.clear();
  pending_.clear();
  std::vector<double> end(d);
  for (std::size_t i = 0; i < candidates_.size(); ++i) {
    Candidate& c = candidates_[i];
    if (const auto it = end_valid_.find(c.state); it != end_valid_.end()) {
      c.ok = it->second;
      continue;
    }
    int ct[kMaxDims];
    layout_.unpack(c.state, ct);
    vertex(ct, end.data());
    batch_.insert(batch_.end(), end.begin(), end.end());
    pending_.push_back(i);
  }
  test(batch_, batch_ok_);
  for (std::size_t j = 0; j < pending_.size(); ++j) {
    Candidate& c = candidates_[pending_[j]];
    c.ok = batch_ok_[j] != 0;
    end_valid_.emplace(c.state, c.ok);
  }
  // Inner samples of every edge whose end passed: one batch, each edge's run of samples
  // recorded so its verdict can be read back.
  batch_.clear();
  pending_.clear();
  std::vector<std::size_t> first;  // each tested edge's first sample in the batch
  double delta[kMaxDims];
  const auto& axes = space_.axes();
  for (std::size_t i = 0; i < candidates_.size(); ++i) {
    Candidate& c = candidates_[i];
    if (!c.ok) continue;
    int ct[kMaxDims];
    layout_.unpack(c.state, ct);
    vertex(ct, end.data());
    double len2 = 0.0;
    for (std::size_t a = 0; a < d; ++a) {
      delta[a] = axis_difference(axes[a], tail_[a], end[a]);
      len2 += delta[a] * delta[a];
    }
    const std::size_t m = motion_steps(std::sqrt(len2), space_.resolution());
    if (m <= 1) continue;  // the end was the only sample
    pending_.push_back(i);
    first.push_back(batch_.size() / d);
    const std::size_t at = batch_.size();
    batch_.resize(at + (m - 1) * d);
    for (std::size_t s = 1; s < m; ++s)
      motion_point(axes, tail_.data(), delta, static_cast<double>(s) / static_cast<double>(m),
                   batch_.data() + at + (s - 1) * d);
  }
  test(batch_, batch_ok_);
  first.push_back(batch_.size() / d);
  for (std::size_t j = 0; j < pending_.size(); ++j) {
    bool ok = true;
    for (std::size_t s = first[j]; s < first[j + 1] && ok; ++s) ok = batch_ok_[s] != 0;
    candidates_[pending_[j]].ok = ok;
  }
}

CSpaceHeuristic::CSpaceHeuristic(const CSpaceGraph& graph, const CSpaceGraph::State& goal)
    : graph_(&graph), dims_(graph.dims()), cells_(graph.cells()) {
  const std::vector<double> g = graph.vertex(goal);
  squared_.resize(static_cast<std::size_t>(dims_) * cells_);
  std::vector<int> c(dims_, 0);
  std::vector<double> q(dims_);
  for (int a = 0; a < dims_; ++a)
    for (int i = 0; i < cells_; ++i) {
      c.assign(dims_, 0);
      c[a] = i;
      graph.vertex(c.data(), q.data());
      const double d = axis_difference(graph.space().axes()[a], q[a], g[a]);
      squared_[static_cast<std::size_t>(a) * cells_ + i] = d * d;
    }
}

}  // namespace hpcplan
