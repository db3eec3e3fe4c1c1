// Exact k-nearest neighbours: depth-first, children in order of their bounds' distance, pruned
// by the current k-th distance.

#include "query/frames.hpp"
#include "query/queries.hpp"

#include <eco/ego_octree.hpp>

#include <algorithm>
#include <limits>

namespace eco {
namespace {

/// Searches into the caller's buffer (no allocation per query): `out` keeps the best so far,
/// nearest first, their points in the anchor frame until the search ends.
class KnnSearch {
 public:
  KnnSearch(const detail::Tree& t, const std::array<double, 3>& q, std::span<Neighbor> out)
      : t_(t), q_(q), out_(out) {}

  /// The number found: min(k, points held).
  std::size_t run() {
    if (!out_.empty() && t_.root() != detail::kNone) visit(t_.root());
    return found_;
  }

 private:
  [[nodiscard]] double worst() const { return worst_; }

  /// Inserts in order: a shift of the farther ones, cheaper than a heap for the small k of
  /// registration (nanoflann's result sets do the same).
  void offer(double d2, const std::array<float, 3>& p) {
    if (found_ < out_.size()) ++found_;
    std::size_t i = found_ - 1;
    for (; i > 0 && out_[i - 1].sq_dist > d2; --i) out_[i] = out_[i - 1];
    out_[i] = {Eigen::Vector3d(p[0], p[1], p[2]), d2};
    if (found_ == out_.size()) worst_ = out_[found_ - 1].sq_dist;
  }

  void visit(std::uint32_t id) {
    const detail::Node& n = t_.nodes()[id];
    if (n.leaf) {
      const detail::PointSpan c = t_.points().span(n.link, n.count);
      for (std::uint32_t i = 0; i < c.size; ++i) {
        const double dx = double(c.x[i]) - q_[0];
        const double dy = double(c.y[i]) - q_[1];
        const double dz = double(c.z[i]) - q_[2];
        const double d2 = dx * dx + dy * dy + dz * dz;
        if (d2 < worst()) offer(d2, {c.x[i], c.y[i], c.z[i]});
      }
      return;
    }
    std::array<std::pair<double, std::uint32_t>, 8> order;
    int m = 0;
    for (int o = 0; o < 8; ++o) {
      const std::uint32_t ch = t_.nodes().child(id, o);
      if (ch != detail::kNone && t_.nodes()[ch].count > 0) {
        order[std::size_t(m++)] = {t_.nodes()[ch].bounds.sq_dist(q_), ch};
      }
    }
    for (int i = 1; i < m; ++i) {  // insertion sort: at most eight children
      for (int j = i; j > 0 && order[std::size_t(j)] < order[std::size_t(j - 1)]; --j) {
        std::swap(order[std::size_t(j)], order[std::size_t(j - 1)]);
      }
    }
    for (int i = 0; i < m; ++i) {
      if (order[std::size_t(i)].first >= worst()) break;
      visit(order[std::size_t(i)].second);
    }
  }

  const detail::Tree& t_;
  std::array<double, 3> q_;
  std::span<Neighbor> out_;
  std::size_t found_ = 0;
  double worst_ = std::numeric_limits<double>::infinity();  // the k-th distance once k are found
};

}  // namespace

namespace detail {

std::size_t knn_query(const Tree& t, const Eigen::Vector3d& query, std::span<Neighbor> out, Frame frame) {
  require_finite(query, "knn", "query");
  const std::size_t found = KnnSearch(t, to_anchor_frame(t, query, frame), out).run();
  for (Neighbor& n : out.first(found)) {  // stored floats, held exactly in double until now
    n.point = from_stored(t, {float(n.point[0]), float(n.point[1]), float(n.point[2])}, frame);
  }
  return found;
}

}  // namespace detail

}  // namespace eco
