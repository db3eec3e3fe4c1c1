#pragma once
// A tree's whole state as plain data, for saving and loading (src/persist): the frame's motion,
// the nodes in pre-order, and their leaves' points column by column in the same order (the root
// cell and lattice follow from the motion: root_placement). layout_of() reads them from a tree in
// place; Tree's restoring constructor puts them back from a file's columns, node for node and point
// for point, so that a restored tree continues exactly as the saved one.

#include "core/geometry/motion.hpp"
#include "core/storage/point_store.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace eco::detail {

class Tree;

/// One node in pre-order: an inner node names its children (bit o: a child in octant o, listed
/// next in octant order); a leaf, how many points it holds (the next that many points).
struct NodeEntry {
  bool leaf = true;
  std::uint8_t children = 0;
  std::uint32_t count = 0;
};

/// A tree to restore: its nodes, and its points as whole columns of 4-byte values in the
/// machine's order, leaf after leaf, read where they lie (a file's bytes: any alignment).
struct TreeParts {
  Motion motion;  ///< frame 0: the tree has taken no frame (and has no root)
  std::vector<NodeEntry> nodes;  ///< empty: no root
  std::size_t point_count = 0;
  ColumnBytes points;  ///< null where the tree does not keep a column
};

/// A tree to save, read in place: its nodes, and its leaves' points in the same order (valid
/// while the tree does not change).
struct TreeLayout {
  Motion motion;
  std::vector<NodeEntry> nodes;
  std::vector<PointSpan> leaves;
  std::size_t point_count = 0;
};

/// The layout of `tree`.
TreeLayout layout_of(const Tree& tree);

}  // namespace eco::detail
