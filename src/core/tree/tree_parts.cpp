// A tree read out as plain data and put back together (tree_parts.hpp).

#include "core/tree/tree_parts.hpp"

#include "core/geometry/subcells.hpp"
#include "core/tree/invariants.hpp"
#include "core/tree/tree.hpp"
#include "core/tree/tree_repair.hpp"

#include <cassert>
#include <optional>
#include <stdexcept>
#include <string>

namespace eco::detail {
namespace {

[[noreturn]] void refuse(const std::string& what) { throw std::invalid_argument(what); }

/// The bounds of `s`'s points, or nothing when a coordinate is not a number (min and max would
/// pass it by).
std::optional<Aabb> bounds_of_numbers(const PointSpan& s) {
  Aabb bounds;
  bool numbers = true;
  for (std::uint32_t i = 0; i < s.size; ++i) {
    bounds.grow(s.x[i], s.y[i], s.z[i]);
    numbers &= s.x[i] == s.x[i] && s.y[i] == s.y[i] && s.z[i] == s.z[i];
  }
  if (!numbers) return std::nullopt;
  return bounds;
}

}  // namespace

TreeLayout layout_of(const Tree& tree) {
  TreeLayout layout;
  layout.motion = tree.motion();
  if (tree.root() == kNone) return layout;
  layout.point_count = tree.size();
  const auto walk = [&](auto&& self, std::uint32_t id) -> void {
    const Node& n = tree.nodes()[id];
    NodeEntry entry{n.leaf, 0, n.leaf ? n.count : 0};
    if (n.leaf) {
      layout.nodes.push_back(entry);
      layout.leaves.push_back(tree.points().span(n.link, n.count));
      return;
    }
    tree.nodes().for_each_child(id, [&](int o, std::uint32_t) { entry.children |= std::uint8_t(1u << o); });
    layout.nodes.push_back(entry);
    tree.nodes().for_each_child(id, [&](int, std::uint32_t ch) { self(self, ch); });
  };
  walk(walk, tree.root());
  return layout;
}

Tree::Tree(const Config& config, const TreeParts& parts) : Tree(config) {
  const ColumnBytes& c = parts.points;
  const std::size_t n = parts.point_count;
  const Columns kept = s_.points().columns();
  const auto present = [&](const std::byte* column, bool is_kept, const char* name) {
    if (n > 0 && (column != nullptr) != is_kept) {
      refuse(std::string("the ") + name + " column is " + (is_kept ? "missing" : "there, but not kept"));
    }
  };
  for_each_column(c, kept, present);
  if (parts.motion.frame == 0) {
    if (!parts.nodes.empty()) refuse("a tree that has taken no frame holds nodes");
    return;
  }
  if (parts.nodes.empty()) refuse("a tree that has taken a frame has no root");
  motion_ = parts.motion;
  s_.set_age(AgeLimit::of(s_.config(), motion_));
  const auto [root_cell, lattice] = root_placement(s_.config(), motion_);
  s_.place(root_cell, lattice);

  // the leaves' blocks in pages mapped at once, when the counts can be the tree's (else the build refuses)
  std::vector<std::uint32_t> counts;
  std::size_t total = 0;
  for (const NodeEntry& entry : parts.nodes) {
    if (!entry.leaf) continue;
    counts.push_back(entry.count);
    total += entry.count;
  }
  if (total == n) s_.points().make_room_for(counts);

  std::size_t next_node = 0;
  std::size_t next_point = 0;
  const auto build = [&](auto&& self, std::uint32_t parent, int octant, const Cell& cell) -> std::uint32_t {
    if (next_node == parts.nodes.size()) refuse("the nodes end inside the tree");
    const std::size_t index = next_node++;
    const NodeEntry& entry = parts.nodes[index];
    const std::uint32_t id = s_.nodes().make_leaf(parent, octant, cell.depth);
    if (entry.leaf) {
      if (cell.depth < s_.min_leaf_depth()) refuse("node " + std::to_string(index) + ": a leaf above the lattice-fixed depth");
      if (entry.count > n - next_point) {
        refuse("node " + std::to_string(index) + ": a leaf of " + std::to_string(entry.count) + " points past the " +
               std::to_string(n - next_point) + " points left");
      }
      if (entry.count > s_.config().leaf_capacity && cell.depth < s_.lattice().max_depth) {
        refuse("node " + std::to_string(index) + ": a leaf of " + std::to_string(entry.count) +
               " points above the deepest level, where N_max = " + std::to_string(s_.config().leaf_capacity));
      }
      Node& leaf = s_.nodes().edit(id);
      s_.points().append_bytes(leaf.link, id, 0, c, next_point, entry.count);
      leaf.count = entry.count;
      // checked in the block, where the copy left them in the cache: cells and the box are
      // products of intervals, so the points lie inside when their bounds do
      const std::optional<Aabb> bounds = bounds_of_numbers(s_.points().span(leaf.link, leaf.count));
      if (!bounds || (entry.count > 0 && (!s_.lattice().contains(cell, *bounds) || !motion_.box.contains_all(*bounds)))) {
        refuse("node " + std::to_string(index) + ": a point of points " + std::to_string(next_point) + ".." +
               std::to_string(next_point + entry.count - 1) + " lies outside its leaf's cell or the ego box");
      }
      next_point += entry.count;
      const bool marks = s_.keeps_subcells() && entry.count > 0;
      TreeRepair(s_).fit_leaf(id, marks ? Subcells(s_.lattice(), cell) : Subcells(), bounds);
    } else {
      if (cell.depth >= s_.lattice().max_depth) refuse("node " + std::to_string(index) + ": an inner node at the deepest level");
      s_.nodes().make_inner(id);
      for (int o = 0; o < 8; ++o) {
        if (entry.children >> o & 1) s_.nodes().edit_child(id, o) = self(self, id, o, s_.lattice().child(cell, o));
      }
      TreeRepair(s_).refit(id);
    }
    if (parent != kNone && s_.nodes()[id].count == 0) refuse("node " + std::to_string(index) + ": an empty node");
    const bool leaf_sized = cell.depth >= s_.min_leaf_depth() && s_.nodes()[id].count <= s_.config().leaf_capacity;
    if (!entry.leaf && parent != kNone && leaf_sized) {
      refuse("node " + std::to_string(index) + ": an inner node of " + std::to_string(s_.nodes()[id].count) +
             " points, which would be a leaf");
    }
    return id;
  };
  s_.set_root(build(build, kNone, 0, s_.root_cell()));
  if (next_node != parts.nodes.size()) refuse(std::to_string(parts.nodes.size() - next_node) + " nodes past the tree");
  if (next_point != n) refuse(std::to_string(n - next_point) + " points past the tree's leaves");
  assert(check_tree(*this).empty());  // every invariant, by the refusals above
}

}  // namespace eco::detail
