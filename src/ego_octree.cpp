// EgoOctree: construction, accessors, iteration and statistics. The update is in update/, the
// queries in query/.

#include "core/tree.hpp"
#include "query/frames.hpp"
#include "query/queries.hpp"

#include <eco/ego_octree.hpp>

namespace eco {

EgoOctree::EgoOctree(const Config& config) : tree_(std::make_unique<detail::Tree>(config)) {}
EgoOctree::~EgoOctree() = default;
EgoOctree::EgoOctree(EgoOctree&&) noexcept = default;
EgoOctree& EgoOctree::operator=(EgoOctree&&) noexcept = default;

std::size_t EgoOctree::size() const {
  return tree_->root == detail::kNone ? 0 : tree_->nodes[tree_->root].count;
}

const UpdateStats& EgoOctree::last_update() const { return tree_->last; }
const Config& EgoOctree::config() const { return tree_->cfg; }
const Eigen::Isometry3d& EgoOctree::pose() const { return tree_->pose(); }
std::uint32_t EgoOctree::frame_count() const { return tree_->frame(); }
Eigen::Vector3d EgoOctree::precision_origin() const { return tree_->anchor(); }

Eigen::AlignedBox3d EgoOctree::ego_box() const {
  if (tree_->frame() == 0) return Eigen::AlignedBox3d();  // empty
  const detail::Box b = tree_->box();
  const Eigen::Vector3d anchor = tree_->anchor();
  return {Eigen::Vector3d(b.lo[0], b.lo[1], b.lo[2]) + anchor, Eigen::Vector3d(b.hi[0], b.hi[1], b.hi[2]) + anchor};
}

void EgoOctree::for_each_point(const std::function<void(const Eigen::Vector3d&)>& visit) const {
  detail::for_each_held(*tree_, visit);
}

std::vector<Eigen::Vector3d> EgoOctree::points() const {
  std::vector<Eigen::Vector3d> out;
  out.reserve(size());
  for_each_point([&](const Eigen::Vector3d& p) { out.push_back(p); });
  return out;
}

Stats EgoOctree::stats() const { return detail::tree_stats(*tree_); }

namespace detail {

void for_each_held(const Tree& t, const std::function<void(const Eigen::Vector3d&)>& visit) {
  if (t.root == kNone) return;
  walk_leaves(
      t, t.root, [](const Aabb&) { return 2; }, [&](const StoredPoint& s, bool) { visit(t.to_world(s.p)); });
}

Stats tree_stats(const Tree& t) {
  Stats s;
  s.points = t.root == kNone ? 0 : t.nodes[t.root].count;
  s.nodes = t.nodes.live();
  s.bytes = sizeof(Tree) + t.nodes.bytes() + t.points.bytes() + t.start.slots.capacity() * sizeof(std::uint32_t) +
            (t.scratch.capacity() + t.batch_buffers.scan.capacity() + t.batch_buffers.points.capacity()) * sizeof(StoredPoint) +
            t.density.bytes();
  if (t.root == kNone) return s;
  double depth_sum = 0.0;
  auto walk = [&](auto&& self, std::uint32_t id) -> void {
    const Node& n = t.nodes[id];
    if (n.leaf) {
      if (n.count == 0) return;
      ++s.leaves;
      depth_sum += n.depth;
      s.max_leaf_depth = std::max(s.max_leaf_depth, int(n.depth));
      return;
    }
    for (int o = 0; o < 8; ++o) {
      const std::uint32_t ch = t.nodes.child(id, o);
      if (ch != kNone) self(self, ch);
    }
  };
  walk(walk, t.root);
  s.mean_leaf_depth = s.leaves ? depth_sum / double(s.leaves) : 0.0;
  return s;
}

}  // namespace detail
}  // namespace eco
