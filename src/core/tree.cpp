#include "core/tree.hpp"

#include <algorithm>
#include <cassert>

namespace eco::detail {

Tree::Tree(const Config& config) : cfg(config), points(config.max_age_frames > 0) {
  cfg.validate();
  min_leaf_depth = cfg.recentring == Recentring::Quantised ? int(cfg.quantum_levels) : 0;
  lattice.max_depth = cfg.max_depth();
}

std::array<float, 3> Tree::to_stored(const Eigen::Vector3d& world) const {
  const Eigen::Vector3d o = anchor();
  return {float(world[0] - o[0]), float(world[1] - o[1]), float(world[2] - o[2])};
}

Eigen::Vector3d Tree::to_world(const std::array<float, 3>& stored) const {
  const Eigen::Vector3d o = anchor();
  return {o[0] + double(stored[0]), o[1] + double(stored[1]), o[2] + double(stored[2])};
}

void Tree::make_root() {
  root = nodes.make_leaf(kNone, 0, 0);
  if (min_leaf_depth > 0) nodes.make_inner(root);
}

// ---------------------------------------------------------------------------------------------
// Insertion

void Tree::insert_batch(std::vector<StoredPoint>& batch) {
  if (batch.empty()) return;
  std::vector<StoredPoint>& temp = batch_buffers.points;
  temp.resize(batch.size());
  // Group the points by their start-depth cell (a counting sort), then insert each group below
  // its start node and add it to the ancestors once.
  const int depth = start.depth;
  std::vector<std::uint32_t>& first = batch_buffers.group_start;
  first.assign((depth == 0 ? 1 : start.slots.size()) + 1, 0);
  if (depth == 0) {
    first[1] = std::uint32_t(batch.size());
  } else {
    std::vector<std::uint32_t>& slot_of = batch_buffers.slot_of;
    slot_of.resize(batch.size());
    for (std::size_t i = 0; i < batch.size(); ++i) {
      const std::int64_t slot = start_slot(lattice.cell_at(depth, batch[i].p));
      assert(slot >= 0);
      slot_of[i] = std::uint32_t(slot);
      ++first[std::size_t(slot) + 1];
    }
    for (std::size_t b = 0; b + 1 < first.size(); ++b) first[b + 1] += first[b];
    std::vector<std::uint32_t>& at = batch_buffers.group_end;
    at.assign(first.begin(), first.end() - 1);
    for (std::size_t i = 0; i < batch.size(); ++i) temp[at[slot_of[i]]++] = batch[i];
    batch.swap(temp);
  }
  for (std::size_t b = 0; b + 1 < first.size(); ++b) {
    if (first[b] == first[b + 1]) continue;
    prefetch_start_node(b + 1, first);
    StoredPoint* group = batch.data() + first[b];
    const std::uint32_t m = first[b + 1] - first[b];
    Cell cell = depth == 0 ? root_cell : lattice.cell_at(depth, group->p);
    const std::uint32_t id = depth == 0 ? root : start_node(cell, cell);
    insert_range(id, cell, group, group + m, temp.data() + first[b]);
    const Node& top = nodes[id];
    for (std::uint32_t up = top.parent; up != kNone; up = nodes[up].parent) {
      Node& n = nodes[up];
      n.count += m;
      n.bounds.merge(top.bounds);
      n.oldest = std::min(n.oldest, top.oldest);
    }
  }
}

void Tree::prefetch_start_node(std::size_t from, const std::vector<std::uint32_t>& first) const {
  if (start.depth == 0) return;
  for (std::size_t b = from; b + 1 < first.size(); ++b) {
    if (first[b] == first[b + 1]) continue;
    if (const std::uint32_t id = start.slots[b]; id != kNone) nodes.prefetch(id);
    return;
  }
}

namespace {

template <class T>
void trim(std::vector<T>& buffer, std::size_t used) {
  constexpr std::size_t kKeep = 1 << 16;  // below this, not worth giving back
  if (buffer.capacity() > kKeep && buffer.capacity() > 4 * used) {
    std::vector<T>().swap(buffer);
    buffer.reserve(used);
  }
}

}  // namespace

void Tree::trim_buffers(std::size_t used) {
  trim(batch_buffers.scan, used);
  trim(batch_buffers.points, used);
  trim(batch_buffers.slot_of, used);
  trim(scratch, used);
}

std::size_t Tree::buffer_bytes() const {
  const BatchBuffers& b = batch_buffers;
  return (scratch.capacity() + b.scan.capacity() + b.points.capacity()) * sizeof(StoredPoint) +
         (b.slot_of.capacity() + b.group_start.capacity() + b.group_end.capacity()) * sizeof(std::uint32_t);
}

std::uint32_t Tree::start_node(const Cell& cell, Cell& at) {
  const std::int64_t slot = start_slot(cell);
  if (slot >= 0 && start.slots[std::size_t(slot)] != kNone) {
    at = cell;
    return start.slots[std::size_t(slot)];
  }
  std::uint32_t id = root;
  const Cell target = cell;
  at = root_cell;
  while (at.depth < target.depth && !nodes[id].leaf) {
    const int o = lattice.octant_of(at, target);
    id = child_or_new(id, at, o);
    at = lattice.child(at, o);
  }
  return id;
}

void Tree::insert_range(std::uint32_t id, const Cell& cell, StoredPoint* from, StoredPoint* to,
                        StoredPoint* temp) {
  const auto m = std::uint32_t(to - from);
  if (nodes[id].leaf && (nodes[id].count + m <= cfg.leaf_capacity || cell.depth >= lattice.max_depth)) {
    Node& n = nodes[id];
    points.append(n.link, n.count, from, to);
    n.count += m;
    for (const StoredPoint* s = from; s != to; ++s) {
      n.bounds.grow(s->p[0], s->p[1], s->p[2]);
      n.oldest = std::min(n.oldest, s->stamp);
    }
    return;
  }
  if (nodes[id].leaf) split(id, cell);  // holds at most leaf_capacity: its children need no split
  nodes.prefetch_children(id);  // their misses overlap the partition below
  // Partition by octant into `temp` (a counting sort); the children read from there and use
  // this range as theirs.
  const std::int64_t half = lattice.side(cell.depth) / 2;
  const std::array<double, 3> wall{lattice.wall(0, cell.lo[0] + half), lattice.wall(1, cell.lo[1] + half),
                                   lattice.wall(2, cell.lo[2] + half)};
  auto octant = [&](const StoredPoint& s) {
    return int(double(s.p[0]) >= wall[0]) | int(double(s.p[1]) >= wall[1]) << 1 |
           int(double(s.p[2]) >= wall[2]) << 2;
  };
  std::array<std::uint32_t, 9> begin{};
  Aabb bounds;
  std::uint32_t oldest = kNone;
  for (const StoredPoint* s = from; s != to; ++s) {
    ++begin[std::size_t(octant(*s)) + 1];
    bounds.grow(s->p[0], s->p[1], s->p[2]);
    oldest = std::min(oldest, s->stamp);
  }
  for (std::size_t o = 0; o < 8; ++o) begin[o + 1] += begin[o];
  std::array<std::uint32_t, 8> at{};
  std::copy(begin.begin(), begin.end() - 1, at.begin());
  for (const StoredPoint* s = from; s != to; ++s) temp[at[std::size_t(octant(*s))]++] = *s;
  Node& n = nodes[id];
  n.count += m;
  n.bounds.merge(bounds);
  n.oldest = std::min(n.oldest, oldest);
  for (int o = 0; o < 8; ++o) {
    const std::uint32_t lo = begin[std::size_t(o)], hi = begin[std::size_t(o) + 1];
    if (lo == hi) continue;
    const std::uint32_t ch = child_or_new(id, cell, o);
    insert_range(ch, lattice.child(cell, o), temp + lo, temp + hi, from + lo);
  }
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
  // Group the points by octant (a counting sort behind them), then hand each child its group.
  const std::size_t m = scratch.size() - base;
  std::array<std::uint32_t, 9> begin{};
  for (std::size_t i = base; i < base + m; ++i) ++begin[std::size_t(lattice.octant(cell, scratch[i].p)) + 1];
  for (std::size_t o = 0; o < 8; ++o) begin[o + 1] += begin[o];
  std::array<std::uint32_t, 8> at{};
  std::copy(begin.begin(), begin.end() - 1, at.begin());
  scratch.resize(base + 2 * m);
  StoredPoint* grouped = scratch.data() + base + m;
  for (std::size_t i = base; i < base + m; ++i) {
    grouped[at[std::size_t(lattice.octant(cell, scratch[i].p))]++] = scratch[i];
  }
  for (int o = 0; o < 8; ++o) {
    const StoredPoint* from = grouped + begin[std::size_t(o)];
    const StoredPoint* to = grouped + begin[std::size_t(o) + 1];
    if (from == to) continue;
    Node& n = nodes[child_or_new(id, cell, o)];
    points.append(n.link, n.count, from, to);
    n.count += std::uint32_t(to - from);
    for (const StoredPoint* s = from; s != to; ++s) {
      n.bounds.grow(s->p[0], s->p[1], s->p[2]);
      n.oldest = std::min(n.oldest, s->stamp);
    }
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
}

void Tree::drop(std::uint32_t id) {
  last.pruned += nodes[id].count;
  if (cfg.density_cap.enabled()) {
    walk_points(id, [&](const StoredPoint& s) { forget(s); });
  }
  dissolve(id, nullptr);
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
  points.append(n.link, 0, scratch.data() + base, scratch.data() + scratch.size());
  n.count = std::uint32_t(scratch.size() - base);
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
