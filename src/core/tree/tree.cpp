// The tree: construction, the frame, memory, the root and re-centring. Insertion is in
// insertion.cpp, the repair its operations share in tree_repair.cpp.

#include "core/tree/tree.hpp"

#include "core/density/density_gate.hpp"
#include "core/tree/tree_repair.hpp"

#include "core/geometry/subcells.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace eco::detail {

Tree::Tree(const Config& config)
    : cfg_(config),
      ledger_(std::make_shared<PageLedger>()),
      points_(Columns{config.max_age_frames > 0, config.attributes.ids, config.attributes.intensity,
                      config.attributes.time},
              ledger_),
      density_(config.density_cap.max_points) {
  cfg_.validate();
  min_leaf_depth_ = min_leaf_depth(cfg_);
  keeps_subcells_ = cfg_.recentring == Recentring::Quantised;
  lattice_.max_depth = cfg_.max_depth();
  age_ = AgeLimit::of(cfg_, motion_);
}

Tree::Tree(Tree& live, Sharing)
    : cfg_(live.cfg_),
      ledger_(live.ledger_),
      nodes_(live.nodes_.share(live.shelf_->take())),
      points_(live.points_.share()),
      root_(live.root_),
      root_cell_(live.root_cell_),
      lattice_(live.lattice_),
      min_leaf_depth_(live.min_leaf_depth_),
      keeps_subcells_(live.keeps_subcells_),
      motion_(live.motion_),
      age_(live.age_),
      density_(cfg_.density_cap.max_points),
      shelf_(live.shelf_),
      own_bytes_(ledger_, nodes_.bytes()),
      snapshot_(true) {
  ++ledger_->snapshots;
}

Tree::~Tree() {
  if (!snapshot_) return;
  --ledger_->snapshots;
  shelf_->put(std::move(nodes_));
}

std::unique_ptr<const Tree> Tree::share() { return std::unique_ptr<const Tree>(new Tree(*this, Sharing{})); }

TreeMemory Tree::memory() const {
  TreeMemory m;
  m.buffer_bytes = buffers_.bytes();
  m.bytes = sizeof(Tree) + nodes_.bytes() + points_.bytes() + start_.slots.capacity() * sizeof(std::uint32_t) +
            m.buffer_bytes + density_.bytes();
  m.snapshot_bytes = ledger_->snapshot_bytes();
  return m;
}

void Tree::set_motion(const Motion& m) {
  motion_ = m;
  age_ = AgeLimit::of(cfg_, m);
  density_grid_ = ego_grid(m, cfg_.density_cap);
  if (m.clock.shift) shift_times(*m.clock.shift);  // in place, nothing moves
}

void Tree::shift_times(double shift) {
  const bool keyed = cfg_.max_age_seconds > 0.0;  // node age keys are read from the times
  auto walk = [&](auto&& self, std::uint32_t id) -> void {
    const Node& n = nodes_[id];
    if (n.leaf) {
      points_.shift_times(n.link, n.count, shift);
    } else {
      nodes_.for_each_child(id, [&](int, std::uint32_t ch) { self(self, ch); });
    }
    if (keyed) TreeRepair(*this).refit(id);
  };
  if (root_ != kNone) walk(walk, root_);
}

std::size_t Tree::judge_density(const std::array<float, 3>* points, std::size_t n, std::uint8_t* passed) {
  return judge_group(density_, density_grid_, cfg_.density_cap, points, n, passed);
}

void Tree::recount_density(const std::vector<StoredPoint>& held) {
  density_.clear();
  if (!cfg_.density_cap.enabled()) return;
  count_in_groups(density_, density_grid_, [&](auto&& add) {
    for (const StoredPoint& s : held) add(s.p);
  });
}

void Tree::give_back_memory(std::size_t floor) {
  compact_points(floor);
  // what this update copied, the next will likely copy again: that much is kept spare
  ledger_->trim_spare(points_.release_replaced());
  if (ledger_->snapshots.load() == 0) (void)shelf_->take();  // no snapshot to copy nodes for soon
}

void Tree::compact_points(std::size_t floor) {
  const std::size_t free = points_.free_bytes();
  if (free == 0 || free < floor || free * kFreeShare < points_.bytes()) return;
  const auto holds = [&](std::uint32_t owner, std::uint32_t link) {
    return owner < nodes_.id_bound() && nodes_[owner].leaf && nodes_[owner].link == link;
  };
  points_.compact(kCompactionBudget, holds, [&](std::uint32_t owner, std::uint32_t link) { nodes_.edit(owner).link = link; });
}

// ---------------------------------------------------------------------------------------------
// The root

void Tree::place_root(const Cell& cell, const Lattice& lattice) {
  if (root_ != kNone) TreeRepair(*this).dissolve(root_, nullptr);
  lattice_ = lattice;
  root_cell_ = cell;
  make_root();
}



void Tree::relink_top(const Cell& new_root, int depth, std::vector<StoredPoint>& displaced, UpdateStats& stats) {
  TreeRepair repair(*this);
  const auto& subtrees = repair.detach_subtrees(depth);
  place_root(new_root, lattice_);
  for (const auto& [id, cell] : subtrees) {
    if (lattice_.encloses(new_root, cell)) {
      repair.attach_subtree(id, cell);
      ++stats.relinked_subtrees;
    } else {  // cannot hold points after shift-out; dissolved for safety all the same
      repair.dissolve(id, &displaced);
      ++stats.rebuilt_subtrees;
    }
  }
  repair.refit_above(depth);
}

void Tree::move_lattice(const Lattice& lattice, std::vector<StoredPoint>& displaced, UpdateStats& stats) {
  lattice_ = lattice;
  if (root_ != kNone) TreeRepair(*this).refit_moved(root_, root_cell_, displaced, stats);
}



void Tree::grow_root(int octant) {
  const std::int64_t side = lattice_.side(0);
  auto deepen = [&](auto&& self, std::uint32_t id) -> void {  // depths count from the root
    ++nodes_.edit(id).depth;
    if (nodes_[id].leaf) return;
    nodes_.for_each_child(id, [&](int, std::uint32_t ch) { self(self, ch); });
  };
  deepen(deepen, root_);
  ++lattice_.max_depth;
  Cell cell{root_cell_.lo, 0};
  for (int a = 0; a < 3; ++a) {
    if (octant >> a & 1) cell.lo[a] -= side;
  }
  const std::uint32_t old_root = root_;
  root_cell_ = cell;
  if (nodes_[old_root].count == 0) {  // nothing to keep: just a bigger empty root
    nodes_.release(old_root);
    make_root();
    return;
  }
  TreeRepair repair(*this);
  if (repair.should_collapse(old_root)) repair.collapse(old_root);  // a root may be small; a child may not
  root_ = nodes_.make_leaf(kNone, 0, 0);
  nodes_.make_inner(root_);
  nodes_.edit_child(root_, octant) = old_root;
  Node& old = nodes_.edit(old_root);
  old.parent = root_;
  old.octant = static_cast<std::uint8_t>(octant);
  repair.refit(root_);
}

void Tree::make_root() {
  root_ = nodes_.make_leaf(kNone, 0, 0);
  if (min_leaf_depth_ > 0) nodes_.make_inner(root_);
}





void Tree::take_points(std::vector<StoredPoint>& out) {
  if (root_ != kNone) TreeRepair(*this).dissolve(root_, &out);
}




}  // namespace eco::detail
