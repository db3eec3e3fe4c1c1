// The tree: construction, the frame, memory, the root and re-centring. Insertion is in
// insertion.cpp, the repair its operations share in tree_repair.cpp.

#include "core/tree/tree.hpp"

#include "core/tree/tree_repair.hpp"

#include "core/geometry/subcells.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace eco::detail {

namespace {

/// `config`, once validate() took it: the storage is sized from it.
const Config& validated(const Config& config) {
  config.validate();
  return config;
}

}  // namespace

Tree::Tree(const Config& config) : s_(validated(config)) { s_.set_age(AgeLimit::of(s_.config(), motion_)); }

Tree::Tree(Tree& live, Sharing)
    : s_(live.s_, live.s_.nodes().share(live.shelf_->take())),
      motion_(live.motion_),
      shelf_(live.shelf_),
      own_bytes_(s_.ledger(), s_.nodes().bytes()),
      snapshot_(true) {
  ++s_.ledger()->snapshots;
}

Tree::~Tree() {
  if (!snapshot_) return;
  --s_.ledger()->snapshots;
  shelf_->put(std::move(s_.nodes()));
}

std::unique_ptr<const Tree> Tree::share() { return std::unique_ptr<const Tree>(new Tree(*this, Sharing{})); }

TreeMemory Tree::memory() const {
  TreeMemory m;
  m.buffer_bytes = s_.buffers().bytes();
  m.bytes = sizeof(Tree) + s_.nodes().bytes() + s_.points().bytes() + s_.start_bytes() + m.buffer_bytes;
  m.snapshot_bytes = s_.ledger()->snapshot_bytes();
  return m;
}

void Tree::set_motion(const Motion& m) {
  motion_ = m;
  s_.set_age(AgeLimit::of(s_.config(), m));
  if (m.clock.shift) shift_times(*m.clock.shift);  // in place, nothing moves
}

void Tree::shift_times(double shift) {
  const bool keyed = s_.config().max_age_seconds > 0.0;  // node age keys are read from the times
  auto walk = [&](auto&& self, std::uint32_t id) -> void {
    const Node& n = s_.nodes()[id];
    if (n.leaf) {
      s_.points().shift_times(n.link, n.count, shift);
    } else {
      s_.nodes().for_each_child(id, [&](int, std::uint32_t ch) { self(self, ch); });
    }
    if (keyed) TreeRepair(s_).refit(id);
  };
  if (s_.root() != kNone) walk(walk, s_.root());
}

void Tree::give_back_memory(std::size_t floor) {
  compact_points(floor);
  // what this update copied, the next will likely copy again: that much is kept spare
  s_.ledger()->trim_spare(s_.points().release_replaced());
  if (s_.ledger()->snapshots.load() == 0) {  // no snapshot to copy nodes or pages for soon
    (void)shelf_->take();
    s_.points().end_sharing();
  }
}

void Tree::compact_points(std::size_t floor) {
  const std::size_t free = s_.points().free_bytes();
  if (free == 0 || free < floor || free * kFreeShare < s_.points().bytes()) return;
  const auto holds = [&](std::uint32_t owner, std::uint32_t link) {
    return owner < s_.nodes().id_bound() && s_.nodes()[owner].leaf && s_.nodes()[owner].link == link;
  };
  const auto relink = [&](std::uint32_t owner, std::uint32_t link) { s_.nodes().edit(owner).link = link; };
  s_.points().compact(kCompactionBudget, holds, relink);
}

// ---------------------------------------------------------------------------------------------
// The root

void Tree::place_root(const Cell& cell, const Lattice& lattice) {
  if (s_.root() != kNone) TreeRepair(s_).dissolve(s_.root(), nullptr);
  s_.place(cell, lattice);
  make_root();
}

void Tree::relink_top(const Cell& new_root, int depth, std::vector<StoredPoint>& displaced, UpdateStats& stats) {
  TreeRepair repair(s_);
  const auto& subtrees = repair.detach_subtrees(depth);
  place_root(new_root, s_.lattice());
  for (const auto& [id, cell] : subtrees) {
    if (s_.lattice().encloses(new_root, cell)) {
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
  s_.place(s_.root_cell(), lattice);
  if (s_.root() != kNone) TreeRepair(s_).refit_moved(s_.root(), s_.root_cell(), displaced, stats);
}

void Tree::grow_root(int octant) {
  const std::int64_t side = s_.lattice().side(0);
  auto deepen = [&](auto&& self, std::uint32_t id) -> void {  // depths count from the root
    ++s_.nodes().edit(id).depth;
    if (s_.nodes()[id].leaf) return;
    s_.nodes().for_each_child(id, [&](int, std::uint32_t ch) { self(self, ch); });
  };
  deepen(deepen, s_.root());
  Lattice deeper = s_.lattice();
  ++deeper.max_depth;
  Cell cell{s_.root_cell().lo, 0};
  for (int a = 0; a < 3; ++a) {
    if (octant >> a & 1) cell.lo[a] -= side;
  }
  const std::uint32_t old_root = s_.root();
  s_.place(cell, deeper);
  if (s_.nodes()[old_root].count == 0) {  // nothing to keep: just a bigger empty root
    s_.nodes().release(old_root);
    make_root();
    return;
  }
  TreeRepair repair(s_);
  if (repair.should_collapse(old_root)) repair.collapse(old_root);  // a root may be small; a child may not
  s_.set_root(s_.nodes().make_leaf(kNone, 0, 0));
  s_.nodes().make_inner(s_.root());
  s_.nodes().edit_child(s_.root(), octant) = old_root;
  Node& old = s_.nodes().edit(old_root);
  old.parent = s_.root();
  old.octant = static_cast<std::uint8_t>(octant);
  repair.refit(s_.root());
}

void Tree::make_root() {
  s_.set_root(s_.nodes().make_leaf(kNone, 0, 0));
  if (s_.min_leaf_depth() > 0) s_.nodes().make_inner(s_.root());
}

void Tree::take_points(std::vector<StoredPoint>& out) {
  if (s_.root() != kNone) TreeRepair(s_).dissolve(s_.root(), &out);
}

}  // namespace eco::detail
