#pragma once
// Nearest-neighbour queries over a growing tree of points, on nanoflann's dynamic KD-tree
// (a logarithmic forest of static trees, so insertions stay cheap).
#include <cstdint>
#include <utility>
#include <vector>

// nanoflann 1.4 leaves a bounding box uninitialised until the first build (harmless here).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <nanoflann.hpp>
#pragma GCC diagnostic pop

#include "hpcplan/env/point.hpp"

namespace hpcplan::tree {

// nanoflann 1.5 renamed SearchParams to SearchParameters and made radius results ResultItem
// (with the same first/second members) instead of std::pair; Debian 12 ships 1.4.2. This is the
// one place that knows.
namespace nanoflann_compat {
#if NANOFLANN_VERSION >= 0x150
using SearchParams = nanoflann::SearchParameters;
template <class Index, class Distance>
using Match = nanoflann::ResultItem<Index, Distance>;
#else
using SearchParams = nanoflann::SearchParams;
template <class Index, class Distance>
using Match = std::pair<Index, Distance>;
#endif
}  // namespace nanoflann_compat

// Threads: one index belongs to one planning run (queries are const but not documented as
// safe for concurrent use by nanoflann).
template <int D>
class PointIndex {
 public:
  // (index, squared distance) pairs from within(): `.first` and `.second` on every version.
  using Matches = std::vector<nanoflann_compat::Match<std::size_t, double>>;

  // `points` is the caller's storage; call added() after each push_back.
  explicit PointIndex(const std::vector<env::Vec<D>>& points)
      : source_{&points}, tree_(D, source_, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {}

  void added(std::size_t i) {
    tree_.addPoints(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i));
  }

  std::size_t nearest(const env::Vec<D>& q) const {
    std::size_t index = 0;
    double d2 = 0.0;
    nanoflann::KNNResultSet<double, std::size_t> result(1);
    result.init(&index, &d2);
    tree_.findNeighbors(result, q.data(), nanoflann_compat::SearchParams());
    return index;
  }

  // Every point within `radius` of q, as (index, squared distance).
  void within(const env::Vec<D>& q, double radius, Matches& out) const {
    nanoflann::RadiusResultSet<double, std::size_t> result(radius * radius, out);
    tree_.findNeighbors(result, q.data(), nanoflann_compat::SearchParams());
  }

 private:
  // nanoflann's dataset adaptor: the points as a read-only table.
  struct Source {
    const std::vector<env::Vec<D>>* points;
    std::size_t kdtree_get_point_count() const { return points->size(); }
    double kdtree_get_pt(std::size_t i, std::size_t k) const { return (*points)[i][k]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
      return false;
    }
  };
  using Tree =
      nanoflann::KDTreeSingleIndexDynamicAdaptor<nanoflann::L2_Simple_Adaptor<double, Source>,
                                                 Source, D>;

  Source source_;
  Tree tree_;
};

}  // namespace hpcplan::tree
