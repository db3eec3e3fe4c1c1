// The tree and its repair: construction, the frame, memory, the root and re-centring, and the
// operations that take points out and put the structure right (refit, dissolve, collapse).
// Insertion is in insertion.cpp.

#include "core/tree.hpp"

#include "core/subcells.hpp"

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
    if (keyed) refit(id);
  };
  if (root_ != kNone) walk(walk, root_);
}

void Tree::recount_density(const std::vector<StoredPoint>& held) {
  density_.clear();
  if (!cfg_.density_cap.enabled()) return;
  count_density([&](auto&& add) {
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
  if (root_ != kNone) dissolve(root_, nullptr);
  lattice_ = lattice;
  root_cell_ = cell;
  make_root();
}

const MappedVector<std::pair<std::uint32_t, Cell>>& Tree::detach_subtrees(int depth) {
  MappedVector<std::pair<std::uint32_t, Cell>>& subtrees = buffers_.detached();
  subtrees.clear();
  auto collect = [&](auto&& self, std::uint32_t id, const Cell& cell) -> void {
    if (cell.depth == depth) {
      subtrees.emplace_back(id, cell);
      return;
    }
    nodes_.for_each_child(id, [&](int o, std::uint32_t ch) { self(self, ch, lattice_.child(cell, o)); });
    nodes_.release(id);
  };
  if (root_ != kNone) collect(collect, root_, root_cell_);
  root_ = kNone;
  return subtrees;
}

void Tree::attach_subtree(std::uint32_t id, const Cell& cell) {
  std::uint32_t parent = root_;
  Cell at = root_cell_;
  while (at.depth < cell.depth - 1) {
    const int o = lattice_.octant_of(at, cell);
    parent = child_or_new(parent, at, o);
    at = lattice_.child(at, o);
  }
  const int o = lattice_.octant_of(at, cell);
  nodes_.edit_child(parent, o) = id;
  Node& n = nodes_.edit(id);
  n.parent = parent;
  n.octant = static_cast<std::uint8_t>(o);
}

void Tree::relink_top(const Cell& new_root, int depth, std::vector<StoredPoint>& displaced, UpdateStats& stats) {
  const auto& subtrees = detach_subtrees(depth);
  place_root(new_root, lattice_);
  for (const auto& [id, cell] : subtrees) {
    if (lattice_.encloses(new_root, cell)) {
      attach_subtree(id, cell);
      ++stats.relinked_subtrees;
    } else {  // cannot hold points after shift-out; dissolved for safety all the same
      dissolve(id, &displaced);
      ++stats.rebuilt_subtrees;
    }
  }
  refit_above(depth);
}

void Tree::move_lattice(const Lattice& lattice, std::vector<StoredPoint>& displaced, UpdateStats& stats) {
  lattice_ = lattice;
  if (root_ != kNone) refit_moved(root_, root_cell_, displaced, stats);
}

void Tree::refit_moved(std::uint32_t id, const Cell& cell, std::vector<StoredPoint>& displaced, UpdateStats& stats) {
  if (nodes_[id].leaf) return;
  nodes_.for_each_child(id, [&](int o, std::uint32_t ch) {
    const Cell child_cell = lattice_.child(cell, o);
    const bool fits = lattice_.contains(child_cell, nodes_[ch].bounds);
    if (fits) refit_moved(ch, child_cell, displaced, stats);
    if (fits && nodes_[ch].count > 0) {
      if (id == root_) ++stats.relinked_subtrees;
      return;
    }
    // everything below moved out of its octant, or the subtree no longer fits it
    if (!fits) ++stats.rebuilt_subtrees;
    dissolve(ch, fits ? nullptr : &displaced);
    nodes_.edit_child(id, o) = kNone;
  });
  refit(id);
  collapse_if_small(id);
}

void Tree::refit_above(int depth) {
  auto walk = [&](auto&& self, std::uint32_t id) -> void {
    if (nodes_[id].depth >= depth) return;
    nodes_.for_each_child(id, [&](int, std::uint32_t ch) { self(self, ch); });
    refit(id);
  };
  if (root_ != kNone) walk(walk, root_);
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
  if (should_collapse(old_root)) collapse(old_root);  // a root may be small; a child may not
  root_ = nodes_.make_leaf(kNone, 0, 0);
  nodes_.make_inner(root_);
  nodes_.edit_child(root_, octant) = old_root;
  Node& old = nodes_.edit(old_root);
  old.parent = root_;
  old.octant = static_cast<std::uint8_t>(octant);
  refit(root_);
}

void Tree::make_root() {
  root_ = nodes_.make_leaf(kNone, 0, 0);
  if (min_leaf_depth_ > 0) nodes_.make_inner(root_);
}

// ---------------------------------------------------------------------------------------------
// Removal and repair

void Tree::refit(std::uint32_t id) {
  const Node& n = nodes_[id];
  if (n.leaf) {
    // a point names its leaf's cell, whose subcells a leaf keeps in Quantised mode
    const PointSpan s = points_.span(n.link, n.count);
    const bool marks = keeps_subcells_ && n.count > 0;
    fit_leaf(id, marks ? Subcells(lattice_, lattice_.cell_at(n.depth, {s.x[0], s.y[0], s.z[0]})) : Subcells());
    return;
  }
  Aabb bounds;
  std::uint32_t oldest = kNone;
  std::uint32_t count = 0;
  nodes_.for_each_child(id, [&](int, std::uint32_t ch) {
    count += nodes_[ch].count;
    bounds.merge(nodes_[ch].bounds);
    oldest = std::min(oldest, nodes_[ch].oldest);
  });
  Node& fitted = nodes_.edit(id);
  fitted.count = count;
  fitted.bounds = bounds;
  fitted.oldest = oldest;
}

void Tree::fit_leaf(std::uint32_t id, const Subcells& quarters) {
  Node& n = nodes_.edit(id);
  const PointSpan s = points_.span(n.link, n.count);
  // column by column, each loop vector code; the age keys read only where a column holds them
  Aabb bounds;
  for (std::uint32_t i = 0; i < n.count; ++i) bounds.grow(s.x[i], s.y[i], s.z[i]);
  const bool aged = s.stamps != nullptr || s.times != nullptr;
  std::uint32_t oldest = n.count > 0 && !aged ? age_.key(StoredPoint{}) : kNone;
  if (aged) {
    for (std::uint32_t i = 0; i < n.count; ++i) oldest = std::min(oldest, age_.key(s[i]));
  }
  std::uint64_t subcells = 0;
  if (keeps_subcells_) {
    for (std::uint32_t i = 0; i < n.count; ++i) subcells |= std::uint64_t{1} << quarters.of({s.x[i], s.y[i], s.z[i]});
  }
  n.set_subcells(subcells);
  n.bounds = bounds;
  n.oldest = oldest;
}

void Tree::dissolve(std::uint32_t id, std::vector<StoredPoint>* out) {
  if (id == root_) root_ = kNone;
  Node& n = nodes_.edit(id);
  if (n.leaf) {
    if (out) {
      points_.drain(n.link, n.count, *out);
    } else {
      points_.release(n.link);
    }
  } else {
    nodes_.for_each_child(id, [&](int, std::uint32_t ch) { dissolve(ch, out); });
  }
  nodes_.release(id);
}

void Tree::drop(std::uint32_t id, UpdateStats& stats) {
  stats.pruned += nodes_[id].count;
  if (cfg_.density_cap.enabled()) {
    forget_in_groups(density_, density_grid_,
                     [&](auto&& offer) { walk_points(id, [&](const StoredPoint& s) { offer(s.p); }); });
  }
  dissolve(id, nullptr);
}

void Tree::take_points(std::vector<StoredPoint>& out) {
  if (root_ != kNone) dissolve(root_, &out);
}

bool Tree::collapse_if_small(std::uint32_t id) {
  if (!should_collapse(id)) return false;
  collapse(id);
  return true;
}

bool Tree::should_collapse(std::uint32_t id) const {
  const Node& n = nodes_[id];
  return !n.leaf && n.depth >= min_leaf_depth_ && n.count <= cfg_.leaf_capacity;
}

void Tree::collapse(std::uint32_t id) {
  std::vector<StoredPoint>& scratch = buffers_.collapsed();
  const std::size_t base = scratch.size();
  nodes_.for_each_child(id, [&](int, std::uint32_t ch) { dissolve(ch, &scratch); });
  nodes_.make_leaf_of_inner(id);
  Node& n = nodes_.edit(id);
  n.count = 0;
  points_.append(n.link, id, 0, scratch.data() + base, scratch.data() + scratch.size());
  n.count = std::uint32_t(scratch.size() - base);
  scratch.resize(base);
  refit(id);  // its subcells (bounds and ages as its children's were)
}

}  // namespace eco::detail
