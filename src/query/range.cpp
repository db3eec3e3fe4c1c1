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

/// Calls visit(stored point) for each held point in the closed box [lo, hi] of the axes
/// `box_pose` places in `frame`: by the world-axis walls when those axes are the world's, else by
/// the turned box (EgoRegion's tests: subtrees wholly inside taken whole, wholly outside skipped).
template <class Visit>
void visit_box(const Tree& t, const Eigen::Isometry3d& box_pose, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
               Frame frame, Visit&& visit) {
  require_finite(lo, "box", "lo");
  require_finite(hi, "box", "hi");
  check_pose(box_pose, "box_pose");
  if ((lo.array() > hi.array()).any()) {
    std::ostringstream s;
    s << "eco::EgoOctree::box: lo = [" << lo.transpose() << "] exceeds hi = [" << hi.transpose()
      << "] on some axis";
    throw std::invalid_argument(s.str());
  }
  if (t.root() == kNone) return;
  const Eigen::Isometry3d world_T_box = world_T_frame(t, frame) * box_pose;
  if (world_T_box.linear() != Eigen::Matrix3d::Identity()) {
    const EgoRegion b = EgoRegion::oriented_box(world_T_box, lo, hi, t.motion().anchor);
    walk_leaves(
        t, t.root(), [&](const Aabb& bounds) { return b.misses(bounds) ? 0 : b.contains_all(bounds) ? 2 : 1; },
        [&](const StoredPoint& s, bool whole) {
          if (whole || b.contains(s.p)) visit(s);
        });
    return;
  }
  Box b;
  b.half_open = false;
  b.lo = to_anchor_frame(t, box_pose * lo, frame);
  b.hi = to_anchor_frame(t, box_pose * hi, frame);
  walk_leaves(
      t, t.root(), [&](const Aabb& bounds) { return b.misses(bounds) ? 0 : b.contains_all(bounds) ? 2 : 1; },
      [&](const StoredPoint& s, bool whole) {
        if (whole || b.contains(s.p[0], s.p[1], s.p[2])) visit(s);
      });
}

}  // namespace

std::vector<Eigen::Vector3d> box_query(const Tree& t, const Eigen::Isometry3d& box_pose, const Eigen::Vector3d& lo,
                                       const Eigen::Vector3d& hi, Frame frame) {
  std::vector<Eigen::Vector3d> out;
  visit_box(t, box_pose, lo, hi, frame, [&](const StoredPoint& s) { out.push_back(from_stored(t, s.p, frame)); });
  return out;
}

std::vector<HeldPoint> box_held_query(const Tree& t, const Eigen::Isometry3d& box_pose, const Eigen::Vector3d& lo,
                                      const Eigen::Vector3d& hi, Frame frame) {
  std::vector<HeldPoint> out;
  visit_box(t, box_pose, lo, hi, frame,
            [&](const StoredPoint& s) { out.push_back({from_stored(t, s.p, frame), attributes_of(t, s)}); });
  return out;
}

}  // namespace detail

}  // namespace eco
