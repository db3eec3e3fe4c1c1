#include "core/tree.hpp"

#include <algorithm>
#include <cassert>

namespace eco::detail {

Tree::Tree(const Config& config) : cfg(config), points(config.max_age_frames > 0) {
  cfg.validate();
  min_leaf_depth = cfg.recentring == Recentring::Quantised ? int(cfg.quantum_levels) : 0;
  lattice.max_depth = cfg.max_depth();
}

Box Tree::box_around(const Eigen::Vector3d& position) const {
  return ego_box(position, anchor, cfg.box_side);
}

std::array<float, 3> Tree::to_stored(const Eigen::Vector3d& world) const {
  return {float(world[0] - anchor[0]), float(world[1] - anchor[1]), float(world[2] - anchor[2])};
}

Eigen::Vector3d Tree::to_world(const std::array<float, 3>& stored) const {
  return {anchor[0] + double(stored[0]), anchor[1] + double(stored[1]),
          anchor[2] + double(stored[2])};
}

void Tree::make_root() {
  root = nodes.make_leaf(kNone, 0, 0);
  if (min_leaf_depth > 0) nodes.make_inner(root);
}

// ---------------------------------------------------------------------------------------------
// Insertion

void Tree::insert(const StoredPoint& s) {
  Cell cell;
  const std::uint32_t leaf = locate(s.p, cell);
  points.push(nodes[leaf].link, nodes[leaf].count, s);
  for (std::uint32_t id = leaf; id != kNone; id = nodes[id].parent) {
    Node& n = nodes[id];
    ++n.count;
    n.bounds.grow(s.p[0], s.p[1], s.p[2]);
    n.oldest = std::min(n.oldest, s.stamp);
  }
  std::uint32_t id = leaf;
  if (nodes[leaf].count > cfg.leaf_capacity && cell.depth < lattice.max_depth) {
    split(leaf, cell);
    while (!nodes[id].leaf) {
      const int o = lattice.octant(cell, s.p);
      id = nodes.child(id, o);
      cell = lattice.child(cell, o);
    }
  }
  finger = {id, cell};
}

std::uint32_t Tree::locate(const std::array<float, 3>& p, Cell& cell) {
  if (finger.leaf != kNone && nodes[finger.leaf].leaf && lattice.contains(finger.cell, p)) {
    cell = finger.cell;
    return finger.leaf;
  }
  std::uint32_t id = root;
  cell = root_cell;
  if (start.depth > 0) {
    const Cell c = lattice.cell_at(start.depth, p);
    const std::int64_t slot = start_slot(c);
    if (slot >= 0 && start.slots[std::size_t(slot)] != kNone) {
      id = start.slots[std::size_t(slot)];
      cell = c;
    }
  }
  while (!nodes[id].leaf) {
    const int o = lattice.octant(cell, p);
    id = child_or_new(id, cell, o);
    cell = lattice.child(cell, o);
  }
  return id;
}

std::uint32_t Tree::child_or_new(std::uint32_t id, const Cell& cell, int octant) {
  std::uint32_t ch = nodes.child(id, octant);
  if (ch != kNone) return ch;
  const int depth = cell.depth + 1;
  ch = nodes.make_leaf(id, octant, depth);
  nodes.child(id, octant) = ch;
  if (depth < min_leaf_depth) nodes.make_inner(ch);
  note_created(ch, lattice.child(cell, octant));
  return ch;
}

void Tree::split(std::uint32_t id, const Cell& cell) {
  const std::size_t base = scratch.size();
  points.drain(nodes[id].link, nodes[id].count, scratch);
  nodes.make_inner(id);
  for (std::size_t i = base; i < scratch.size(); ++i) {
    const StoredPoint s = scratch[i];
    const std::uint32_t ch = child_or_new(id, cell, lattice.octant(cell, s.p));
    Node& n = nodes[ch];
    points.push(n.link, n.count, s);
    ++n.count;
    n.bounds.grow(s.p[0], s.p[1], s.p[2]);
    n.oldest = std::min(n.oldest, s.stamp);
  }
  scratch.resize(base);
  for (int o = 0; o < 8; ++o) {
    const std::uint32_t ch = nodes.child(id, o);
    if (ch != kNone && nodes[ch].count > cfg.leaf_capacity && cell.depth + 1 < lattice.max_depth) {
      split(ch, lattice.child(cell, o));
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Removal and repair

void Tree::refit(std::uint32_t id) {
  Node& n = nodes[id];
  Aabb bounds;
  std::uint32_t oldest = kNone;
  if (n.leaf) {
    points.for_each(n.link, n.count, [&](const StoredPoint& s) {
      bounds.grow(s.p[0], s.p[1], s.p[2]);
      oldest = std::min(oldest, s.stamp);
    });
  } else {
    std::uint32_t count = 0;
    for (int o = 0; o < 8; ++o) {
      const std::uint32_t ch = nodes.child(id, o);
      if (ch == kNone) continue;
      count += nodes[ch].count;
      bounds.merge(nodes[ch].bounds);
      oldest = std::min(oldest, nodes[ch].oldest);
    }
    nodes[id].count = count;
  }
  nodes[id].bounds = bounds;
  nodes[id].oldest = oldest;
}

void Tree::dissolve(std::uint32_t id, std::vector<StoredPoint>* out) {
  Node& n = nodes[id];
  if (n.leaf) {
    if (out) {
      points.drain(n.link, n.count, *out);
    } else {
      points.release(n.link);
    }
  } else {
    for (int o = 0; o < 8; ++o) {
      const std::uint32_t ch = nodes.child(id, o);
      if (ch != kNone) dissolve(ch, out);
    }
  }
  nodes.release(id);
  finger = {};
}

bool Tree::should_collapse(std::uint32_t id) const {
  const Node& n = nodes[id];
  return !n.leaf && n.depth >= min_leaf_depth && n.count <= cfg.leaf_capacity;
}

void Tree::collapse(std::uint32_t id) {
  const std::size_t base = scratch.size();
  for (int o = 0; o < 8; ++o) {
    const std::uint32_t ch = nodes.child(id, o);
    if (ch != kNone) dissolve(ch, &scratch);
  }
  nodes.make_leaf_of_inner(id);
  Node& n = nodes[id];
  n.count = 0;
  for (std::size_t i = base; i < scratch.size(); ++i) points.push(n.link, n.count++, scratch[i]);
  scratch.resize(base);
}

// ---------------------------------------------------------------------------------------------
// Start table

std::int64_t Tree::start_slot(const Cell& cell) const {
  const std::int64_t side = lattice.side(start.depth);
  std::int64_t slot = 0;
  for (int a = 2; a >= 0; --a) {
    const std::int64_t rel = (cell.lo[a] - root_cell.lo[a]) / side;
    if (cell.lo[a] < root_cell.lo[a] || rel >= start.per_axis) return -1;
    slot = slot * start.per_axis + rel;
  }
  return slot;
}

void Tree::note_created(std::uint32_t id, const Cell& cell) {
  if (start.depth == 0 || cell.depth != start.depth) return;
  const std::int64_t slot = start_slot(cell);
  if (slot >= 0) start.slots[std::size_t(slot)] = id;
}

void Tree::rebuild_start_table(int depth) {
  start.depth = depth;
  start.per_axis = std::int64_t{1} << depth;
  start.slots.assign(depth == 0 ? 0 : std::size_t(start.per_axis * start.per_axis * start.per_axis),
                     kNone);
  finger = {};
  if (depth == 0) return;
  auto walk = [&](auto&& self, std::uint32_t id, const Cell& cell) -> void {
    if (cell.depth == depth) {
      note_created(id, cell);
      return;
    }
    if (nodes[id].leaf) return;
    for (int o = 0; o < 8; ++o) {
      const std::uint32_t ch = nodes.child(id, o);
      if (ch != kNone) self(self, ch, lattice.child(cell, o));
    }
  };
  walk(walk, root, root_cell);
}

}  // namespace eco::detail
