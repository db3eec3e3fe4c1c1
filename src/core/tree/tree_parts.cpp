// A tree taken apart into plain data and put back together (tree_parts.hpp).

#include "core/tree/tree_parts.hpp"

#include "core/tree/invariants.hpp"
#include "core/tree/tree.hpp"
#include "core/tree/tree_repair.hpp"

#include <cassert>
#include <stdexcept>
#include <string>

namespace eco::detail {
namespace {

template <class T>
void append_column(std::vector<T>& to, const T* from, std::uint32_t n) {
  if (from != nullptr) to.insert(to.end(), from, from + n);
}

[[noreturn]] void refuse(const std::string& what) { throw std::invalid_argument(what); }

}  // namespace

TreeParts parts_of(const Tree& tree) {
  TreeParts parts;
  parts.motion = tree.motion();
  if (tree.root() == kNone) return parts;
  TreeParts::Columns& c = parts.points;
  const Columns kept = tree.points().columns();
  for (auto* column : {&c.x, &c.y, &c.z}) column->reserve(tree.size());
  if (kept.stamps) c.stamps.reserve(tree.size());
  if (kept.ids) c.ids.reserve(tree.size());
  if (kept.intensities) c.intensities.reserve(tree.size());
  if (kept.times) c.times.reserve(tree.size());
  const auto walk = [&](auto&& self, std::uint32_t id) -> void {
    const Node& n = tree.nodes()[id];
    TreeParts::NodeEntry entry{n.leaf, 0, n.leaf ? n.count : 0};
    if (n.leaf) {
      parts.nodes.push_back(entry);
      const PointSpan s = tree.points().span(n.link, n.count);
      append_column(c.x, s.x, n.count);
      append_column(c.y, s.y, n.count);
      append_column(c.z, s.z, n.count);
      append_column(c.stamps, s.stamps, n.count);
      append_column(c.ids, s.ids, n.count);
      append_column(c.intensities, s.intensities, n.count);
      append_column(c.times, s.times, n.count);
      return;
    }
    tree.nodes().for_each_child(id, [&](int o, std::uint32_t) { entry.children |= std::uint8_t(1u << o); });
    parts.nodes.push_back(entry);
    tree.nodes().for_each_child(id, [&](int, std::uint32_t ch) { self(self, ch); });
  };
  walk(walk, tree.root());
  return parts;
}

Tree::Tree(const Config& config, const TreeParts& parts) : Tree(config) {
  const TreeParts::Columns& c = parts.points;
  const std::size_t n = c.x.size();
  const auto sized = [&](std::size_t size, bool kept, const char* name) {
    if (size != (kept ? n : 0)) {
      refuse(std::string("the ") + name + " column holds " + std::to_string(size) + " values for " +
             std::to_string(n) + " points");
    }
  };
  sized(c.y.size(), true, "y");
  sized(c.z.size(), true, "z");
  const Columns kept = s_.points.columns();
  sized(c.stamps.size(), kept.stamps, "stamps");
  sized(c.ids.size(), kept.ids, "ids");
  sized(c.intensities.size(), kept.intensities, "intensities");
  sized(c.times.size(), kept.times, "times");
  if (parts.motion.frame == 0) {
    if (!parts.nodes.empty()) refuse("a tree that has taken no frame holds nodes");
    return;
  }
  if (parts.nodes.empty()) refuse("a tree that has taken a frame has no root");
  motion_ = parts.motion;
  s_.age = AgeLimit::of(s_.config, motion_);
  s_.density.enter(motion_);
  std::tie(s_.root_cell, s_.lattice) = root_placement(s_.config, motion_);

  std::size_t next_node = 0;
  std::size_t next_point = 0;
  const auto build = [&](auto&& self, std::uint32_t parent, int octant, const Cell& cell) -> std::uint32_t {
    if (next_node == parts.nodes.size()) refuse("the nodes end inside the tree");
    const std::size_t index = next_node++;
    const TreeParts::NodeEntry& entry = parts.nodes[index];
    const std::uint32_t id = s_.nodes.make_leaf(parent, octant, cell.depth);
    if (entry.leaf) {
      if (cell.depth < s_.min_leaf_depth) refuse("node " + std::to_string(index) + ": a leaf above the lattice-fixed depth");
      if (entry.count > n - next_point) {
        refuse("node " + std::to_string(index) + ": a leaf of " + std::to_string(entry.count) + " points past the " +
               std::to_string(n - next_point) + " points left");
      }
      if (entry.count > s_.config.leaf_capacity && cell.depth < s_.lattice.max_depth) {
        refuse("node " + std::to_string(index) + ": a leaf of " + std::to_string(entry.count) +
               " points above the deepest level, where N_max = " + std::to_string(s_.config.leaf_capacity));
      }
      const auto at = [&](const auto& column) { return column.empty() ? nullptr : column.data() + next_point; };
      const PointSpan span{at(c.x),   at(c.y),  at(c.z),           at(c.stamps),
                           at(c.ids), at(c.intensities), at(c.times), entry.count};
      // cells and the box are products of intervals: the points lie inside when their bounds do
      Aabb bounds;
      bool numbers = true;
      for (std::uint32_t i = 0; i < entry.count; ++i) {
        bounds.grow(span.x[i], span.y[i], span.z[i]);
        numbers &= span.x[i] == span.x[i] && span.y[i] == span.y[i] && span.z[i] == span.z[i];
      }
      if (!numbers || (entry.count > 0 && (!s_.lattice.contains(cell, bounds) || !motion_.box.contains_all(bounds)))) {
        refuse("node " + std::to_string(index) + ": a point of points " + std::to_string(next_point) + ".." +
               std::to_string(next_point + entry.count - 1) + " lies outside its leaf's cell or the ego box");
      }
      Node& leaf = s_.nodes.edit(id);
      s_.points.append_span(leaf.link, id, 0, span);
      leaf.count = entry.count;
      next_point += entry.count;
    } else {
      if (cell.depth >= s_.lattice.max_depth) refuse("node " + std::to_string(index) + ": an inner node at the deepest level");
      s_.nodes.make_inner(id);
      for (int o = 0; o < 8; ++o) {
        if (entry.children >> o & 1) s_.nodes.edit_child(id, o) = self(self, id, o, s_.lattice.child(cell, o));
      }
    }
    TreeRepair(s_).refit(id);
    if (parent != kNone && s_.nodes[id].count == 0) refuse("node " + std::to_string(index) + ": an empty node");
    if (!entry.leaf && parent != kNone && cell.depth >= s_.min_leaf_depth && s_.nodes[id].count <= s_.config.leaf_capacity) {
      refuse("node " + std::to_string(index) + ": an inner node of " + std::to_string(s_.nodes[id].count) +
             " points, which would be a leaf");
    }
    return id;
  };
  s_.root = build(build, kNone, 0, s_.root_cell);
  if (next_node != parts.nodes.size()) refuse(std::to_string(parts.nodes.size() - next_node) + " nodes past the tree");
  if (next_point != n) refuse(std::to_string(n - next_point) + " points past the tree's leaves");
  s_.density.recount([&](auto&& add) { TreeRepair(s_).walk_points(s_.root, [&](const StoredPoint& s) { add(s.p); }); });
  assert(check_tree(*this).empty());  // every invariant, by the refusals above
}

}  // namespace eco::detail
