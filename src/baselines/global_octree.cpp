#include "baselines/global_octree.hpp"

#include "update/stages.hpp"

#include <cmath>
#include <optional>

namespace eco::baselines {
namespace {

Config fixed_root(Config config) {
  config.recentring = Recentring::Exact;  // no lattice quantum: the root is placed once
  return config;
}

/// The first root: the cell of side L on the first box.
detail::Lattice first_lattice(const Config& config, const detail::Box& box) {
  detail::Lattice lattice;
  lattice.max_depth = config.max_depth();
  lattice.unit = std::ldexp(config.box_side, -lattice.max_depth);
  lattice.origin = box.lo;
  return lattice;
}

/// None when the root's cell holds all of `box`; else the octant the old root takes in a root
/// twice its size that grows toward the box (down on each axis where the box sticks out below).
std::optional<int> growth_toward(const detail::Tree& t, const detail::Box& box) {
  const detail::Lattice& lattice = t.lattice();
  const std::int64_t side = lattice.side(0);
  bool covered = true;
  int octant = 0;
  for (int a = 0; a < 3; ++a) {
    const double lo = lattice.wall(a, t.root_cell().lo[a]), hi = lattice.wall(a, t.root_cell().lo[a] + side);
    if (box.lo[a] < lo) octant |= 1 << a;
    covered = covered && box.lo[a] >= lo && box.hi[a] <= hi;
  }
  return covered ? std::nullopt : std::optional<int>(octant);
}

}  // namespace

GlobalOctree::GlobalOctree(std::string name, const Config& config, bool deletes)
    : TreeMethod(std::move(name), fixed_root(config)), deletes_(deletes) {}

void GlobalOctree::update(const Eigen::Isometry3d& world_T_sensor, ScanView scan) {
  detail::Tree& t = tree_;
  UpdateStats stats = detail::begin_update(t.config(), world_T_sensor, scan);
  detail::ClearingState* clearing = clearing_.get();
  detail::DensityCells* density = density_.get();
  if (clearing) detail::release_arrivals(t, density, *clearing, stats);  // the last update's arrivals into space seen empty
  // the precision origin stays where the drive began, like the root
  const detail::Motion motion = detail::advance_ego_motion_fixed_origin(t, density, world_T_sensor, scan);
  if (t.root() == detail::kNone) t.place_root(detail::Cell{}, first_lattice(t.config(), motion.box));
  if (deletes_) detail::prune_shift_out(t, density, motion, stats);
  std::vector<detail::StoredPoint> none;  // the origin never moves: nothing is handed on
  if (clearing) detail::clear_free_space(t, density, *clearing, motion, scan, none, stats);
  while (const std::optional<int> octant = growth_toward(t, motion.box)) t.grow_root(*octant);
  detail::insert_scan(t, density, motion, scan, clearing, stats);  // from the root: the doubled roots sit off ECO's lattice
}

}  // namespace eco::baselines
