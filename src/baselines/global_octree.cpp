#include "baselines/global_octree.hpp"

#include "update/stages.hpp"

#include <cmath>

namespace eco::baselines {
namespace {

Config fixed_root(Config config) {
  config.recentring = Recentring::Exact;  // no lattice quantum: the root is placed once
  return config;
}

}  // namespace

GlobalOctree::GlobalOctree(std::string name, const Config& config, bool deletes)
    : TreeMethod(std::move(name), fixed_root(config)), deletes_(deletes) {}

void GlobalOctree::update(const Eigen::Isometry3d& world_T_sensor, ScanView scan) {
  detail::check_update_arguments(world_T_sensor, "world_T_sensor", scan, tree_.cfg);
  detail::Tree& t = tree_;
  t.last = UpdateStats{};
  t.last.scan_points = scan.count;
  // the precision origin stays where the drive began, like the root
  const detail::Motion motion = detail::advance_ego_motion_fixed_origin(t, world_T_sensor);
  if (t.root == detail::kNone) place_first_root(motion.box);
  if (deletes_) detail::prune_shift_out(t, motion);
  grow_to_cover(motion.box);
  detail::insert_scan(t, motion, scan);  // from the root: the doubled roots sit off ECO's lattice
}

void GlobalOctree::place_first_root(const detail::Box& box) {
  detail::Tree& t = tree_;
  t.lattice.unit = std::ldexp(t.cfg.box_side, -t.lattice.max_depth);
  t.lattice.origin = box.lo;
  t.root_cell = detail::Cell{};
  t.make_root();
}

void GlobalOctree::grow_to_cover(const detail::Box& box) {
  const detail::Tree& t = tree_;
  auto covered = [&] {
    const std::int64_t side = t.lattice.side(0);
    for (int a = 0; a < 3; ++a) {
      if (box.lo[a] < t.lattice.wall(a, t.root_cell.lo[a]) || box.hi[a] > t.lattice.wall(a, t.root_cell.lo[a] + side)) {
        return false;
      }
    }
    return true;
  };
  while (!covered()) grow_once(box);
}

void GlobalOctree::grow_once(const detail::Box& box) {
  detail::Tree& t = tree_;
  const std::int64_t side = t.lattice.side(0);
  // Every level moves one down: depths are counted from the root.
  auto deepen = [&](auto&& self, std::uint32_t id) -> void {
    ++t.nodes[id].depth;
    if (t.nodes[id].leaf) return;
    for (int o = 0; o < 8; ++o) {
      const std::uint32_t ch = t.nodes.child(id, o);
      if (ch != detail::kNone) self(self, ch);
    }
  };
  deepen(deepen, t.root);
  ++t.lattice.max_depth;
  // The old root becomes the child on the side away from the box.
  detail::Cell cell{t.root_cell.lo, 0};
  int octant = 0;
  for (int a = 0; a < 3; ++a) {
    if (box.lo[a] < t.lattice.wall(a, t.root_cell.lo[a])) {
      cell.lo[a] -= side;
      octant |= 1 << a;
    }
  }
  const std::uint32_t old_root = t.root;
  t.root_cell = cell;
  if (t.nodes[old_root].count == 0) {  // nothing to keep: just a bigger empty root
    t.nodes.release(old_root);
    t.make_root();
    return;
  }
  if (t.should_collapse(old_root)) t.collapse(old_root);  // a root may be small; a child may not
  t.root = t.nodes.make_leaf(detail::kNone, 0, 0);
  t.nodes.make_inner(t.root);
  t.nodes.child(t.root, octant) = old_root;
  t.nodes[old_root].parent = t.root;
  t.nodes[old_root].octant = static_cast<std::uint8_t>(octant);
  t.refit(t.root);
}

}  // namespace eco::baselines
