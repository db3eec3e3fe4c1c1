// Whole-map reads: every held point, and the tree's statistics.

#include "query/frames.hpp"
#include "query/queries.hpp"

#include <algorithm>

namespace eco::detail {

void for_each_held(const Tree& t, const std::function<void(const Eigen::Vector3d&)>& visit) {
  if (t.root() == kNone) return;
  walk_leaves(
      t, t.root(), [](const Aabb&) { return 2; }, [&](const StoredPoint& s, bool) { visit(t.motion().to_world(s.p)); });
}

void copy_held(const Tree& t, const Eigen::Vector3d& origin, float* out) {
  if (t.root() == kNone) return;
  const Eigen::Vector3d anchor = t.motion().anchor;
  const auto walk = [&](auto&& self, std::uint32_t id) -> void {
    const Node& n = t.nodes()[id];
    if (n.count == 0) return;
    if (!n.leaf) {
      t.nodes().for_each_child(id, [&](int, std::uint32_t child) { self(self, child); });
      return;
    }
    const PointSpan s = t.points().span(n.link, n.count);
    for (std::uint32_t i = 0; i < s.size; ++i, out += 3) {  // as to_world, then less the origin
      out[0] = float((anchor[0] + double(s.x[i])) - origin[0]);
      out[1] = float((anchor[1] + double(s.y[i])) - origin[1]);
      out[2] = float((anchor[2] + double(s.z[i])) - origin[2]);
    }
  };
  walk(walk, t.root());
}

std::vector<HeldPoint> held_points(const Tree& t) {
  std::vector<HeldPoint> out;
  out.reserve(t.size());
  if (t.root() == kNone) return out;
  walk_leaves(
      t, t.root(), [](const Aabb&) { return 2; },
      [&](const StoredPoint& s, bool) { out.push_back({t.motion().to_world(s.p), attributes_of(t, s)}); });
  return out;
}

Stats tree_stats(const Tree& t) {
  Stats s;
  s.points = t.size();
  s.nodes = t.nodes().live();
  const TreeMemory memory = t.memory();
  s.bytes = memory.bytes;
  s.snapshot_bytes = memory.snapshot_bytes;
  if (t.root() == kNone) return s;
  double depth_sum = 0.0;
  auto walk = [&](auto&& self, std::uint32_t id) -> void {
    const Node& n = t.nodes()[id];
    if (n.leaf) {
      if (n.count == 0) return;
      ++s.leaves;
      depth_sum += n.depth;
      s.max_leaf_depth = std::max(s.max_leaf_depth, int(n.depth));
      return;
    }
    t.nodes().for_each_child(id, [&](int, std::uint32_t ch) { self(self, ch); });
  };
  walk(walk, t.root());
  s.mean_leaf_depth = s.leaves ? depth_sum / double(s.leaves) : 0.0;
  return s;
}

}  // namespace eco::detail
