// Radius and box queries: subtrees are skipped or taken whole by their bounds.

#include "query/frames.hpp"

#include <eco/ego_octree.hpp>

#include <algorithm>

namespace eco {

std::vector<Neighbor> EgoOctree::radius(const Eigen::Vector3d& query, double radius,
                                        Frame frame) const {
  detail::require_finite(query, "radius", "query");
  detail::require_positive(radius, "radius", "radius", true);
  const detail::Tree& t = *tree_;
  const std::array<double, 3> q = detail::to_anchor_frame(t, query, frame);
  const double r2 = radius * radius;
  std::vector<Neighbor> out;
  if (t.root == detail::kNone) return out;
  detail::walk_leaves(
      t, t.root, [&](const detail::Aabb& b) { return b.sq_dist(q) <= r2 ? 1 : 0; },
      [&](const detail::StoredPoint& s, bool) {
        const double dx = double(s.p[0]) - q[0];
        const double dy = double(s.p[1]) - q[1];
        const double dz = double(s.p[2]) - q[2];
        const double d2 = dx * dx + dy * dy + dz * dz;
        if (d2 <= r2) out.push_back({detail::from_stored(t, s.p, frame), d2});
      });
  std::sort(out.begin(), out.end(),
            [](const Neighbor& a, const Neighbor& b) { return a.sq_dist < b.sq_dist; });
  return out;
}

std::vector<Eigen::Vector3d> EgoOctree::box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                                            Frame frame) const {
  detail::require_finite(lo, "box", "lo");
  detail::require_finite(hi, "box", "hi");
  if ((lo.array() > hi.array()).any()) {
    std::ostringstream s;
    s << "eco::EgoOctree::box: lo = [" << lo.transpose() << "] exceeds hi = [" << hi.transpose()
      << "] on some axis";
    throw std::invalid_argument(s.str());
  }
  const detail::Tree& t = *tree_;
  detail::Box b;
  b.half_open = false;
  b.lo = detail::to_anchor_frame(t, lo, frame);
  b.hi = detail::to_anchor_frame(t, hi, frame);
  std::vector<Eigen::Vector3d> out;
  if (t.root == detail::kNone) return out;
  detail::walk_leaves(
      t, t.root,
      [&](const detail::Aabb& bounds) { return b.misses(bounds) ? 0 : b.contains_all(bounds) ? 2 : 1; },
      [&](const detail::StoredPoint& s, bool whole) {
        if (whole || b.contains(s.p[0], s.p[1], s.p[2])) out.push_back(detail::from_stored(t, s.p, frame));
      });
  return out;
}

}  // namespace eco
