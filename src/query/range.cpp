// Radius and box queries: subtrees are skipped or taken whole by their bounds.

#include "query/frames.hpp"
#include "query/queries.hpp"


#include <algorithm>

namespace eco {
namespace detail {

std::vector<Neighbor> radius_query(const Tree& t, const Eigen::Vector3d& query, double radius, Frame frame) {
  require_finite(query, "radius", "query");
  require_positive(radius, "radius", "radius", true);
  const std::array<double, 3> q = to_anchor_frame(t, query, frame);
  const double r2 = radius * radius;
  std::vector<Neighbor> out;
  if (t.root() == kNone) return out;
  walk_leaves(
      t, t.root(), [&](const Aabb& b) { return b.sq_dist(q) <= r2 ? 1 : 0; },
      [&](const StoredPoint& s, bool) {
        const double dx = double(s.p[0]) - q[0];
        const double dy = double(s.p[1]) - q[1];
        const double dz = double(s.p[2]) - q[2];
        const double d2 = dx * dx + dy * dy + dz * dz;
        if (d2 <= r2) out.push_back({from_stored(t, s.p, frame), d2, attributes_of(t, s)});
      });
  std::sort(out.begin(), out.end(),
            [](const Neighbor& a, const Neighbor& b) { return a.sq_dist < b.sq_dist; });
  return out;
}

namespace {

/// Calls visit(stored point) for each held point in the closed box [lo, hi] given in `frame`.
template <class Visit>
void visit_box(const Tree& t, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, Frame frame, Visit&& visit) {
  require_finite(lo, "box", "lo");
  require_finite(hi, "box", "hi");
  if ((lo.array() > hi.array()).any()) {
    std::ostringstream s;
    s << "eco::EgoOctree::box: lo = [" << lo.transpose() << "] exceeds hi = [" << hi.transpose()
      << "] on some axis";
    throw std::invalid_argument(s.str());
  }
  Box b;
  b.half_open = false;
  b.lo = to_anchor_frame(t, lo, frame);
  b.hi = to_anchor_frame(t, hi, frame);
  if (t.root() == kNone) return;
  walk_leaves(
      t, t.root(), [&](const Aabb& bounds) { return b.misses(bounds) ? 0 : b.contains_all(bounds) ? 2 : 1; },
      [&](const StoredPoint& s, bool whole) {
        if (whole || b.contains(s.p[0], s.p[1], s.p[2])) visit(s);
      });
}

}  // namespace

std::vector<Eigen::Vector3d> box_query(const Tree& t, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                                       Frame frame) {
  std::vector<Eigen::Vector3d> out;
  visit_box(t, lo, hi, frame, [&](const StoredPoint& s) { out.push_back(from_stored(t, s.p, frame)); });
  return out;
}

std::vector<HeldPoint> box_held_query(const Tree& t, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                                      Frame frame) {
  std::vector<HeldPoint> out;
  visit_box(t, lo, hi, frame,
            [&](const StoredPoint& s) { out.push_back({from_stored(t, s.p, frame), attributes_of(t, s)}); });
  return out;
}

}  // namespace detail

}  // namespace eco
