// Exact k-nearest neighbours: depth-first, children in order of their bounds' distance, pruned
// by the current k-th distance.

#include "query/frames.hpp"
#include "query/queries.hpp"

#include <eco/ego_octree.hpp>

#include <algorithm>
#include <limits>

namespace eco {
namespace {

struct Candidate {
  double sq_dist;
  std::array<float, 3> p;
  bool operator<(const Candidate& o) const { return sq_dist < o.sq_dist; }
};

class KnnSearch {
 public:
  KnnSearch(const detail::Tree& t, const std::array<double, 3>& q, std::size_t k) : t_(t), q_(q), k_(k) {
    heap_.reserve(k);
  }

  std::vector<Candidate>& run() {
    if (k_ > 0 && t_.root != detail::kNone) visit(t_.root);
    std::sort_heap(heap_.begin(), heap_.end());
    return heap_;
  }

 private:
  [[nodiscard]] double worst() const {
    return heap_.size() < k_ ? std::numeric_limits<double>::infinity() : heap_.front().sq_dist;
  }

  void offer(double d2, const std::array<float, 3>& p) {
    if (heap_.size() < k_) {
      heap_.push_back({d2, p});
      std::push_heap(heap_.begin(), heap_.end());
    } else if (d2 < heap_.front().sq_dist) {
      std::pop_heap(heap_.begin(), heap_.end());
      heap_.back() = {d2, p};
      std::push_heap(heap_.begin(), heap_.end());
    }
  }

  void visit(std::uint32_t id) {
    const detail::Node& n = t_.nodes[id];
    if (n.leaf) {
      const detail::PointSpan c = t_.points.span(n.link, n.count);
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
      const std::uint32_t ch = t_.nodes.child(id, o);
      if (ch != detail::kNone && t_.nodes[ch].count > 0) {
        order[std::size_t(m++)] = {t_.nodes[ch].bounds.sq_dist(q_), ch};
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
  std::size_t k_;
  std::vector<Candidate> heap_;
};

}  // namespace

namespace detail {

std::size_t knn_query(const Tree& t, const Eigen::Vector3d& query, std::span<Neighbor> out, Frame frame) {
  require_finite(query, "knn", "query");
  KnnSearch search(t, to_anchor_frame(t, query, frame), out.size());
  const std::vector<Candidate>& found = search.run();
  for (std::size_t i = 0; i < found.size(); ++i) {
    out[i] = {from_stored(t, found[i].p, frame), found[i].sq_dist};
  }
  return found.size();
}

}  // namespace detail

std::size_t EgoOctree::knn(const Eigen::Vector3d& query, std::span<Neighbor> out, Frame frame) const {
  return detail::knn_query(*tree_, query, out, frame);
}

std::vector<Neighbor> EgoOctree::knn(const Eigen::Vector3d& query, std::size_t k, Frame frame) const {
  std::vector<Neighbor> out(std::min<std::size_t>(k, size()));
  out.resize(knn(query, std::span<Neighbor>(out), frame));
  return out;
}

}  // namespace eco
