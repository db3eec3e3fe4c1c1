#pragma once
// A tree's whole state as plain data, for saving and loading (src/persist): the frame's motion,
// the nodes in pre-order, and their leaves' points column by column in the same order (the root
// cell and lattice follow from the motion: root_placement). parts_of() takes them from a tree;
// Tree's restoring constructor puts them back, node for node and point for point, so that a
// restored tree continues exactly as the saved one.

#include "core/geometry/motion.hpp"

#include <cstdint>
#include <vector>

namespace eco::detail {

class Tree;

struct TreeParts {
  /// One node in pre-order: an inner node names its children (bit o: a child in octant o, listed
  /// next in octant order); a leaf, how many points it holds (the next that many in `points`).
  struct NodeEntry {
    bool leaf = true;
    std::uint8_t children = 0;
    std::uint32_t count = 0;
  };
  /// The points of every leaf, leaf after leaf: the coordinates, then the columns the tree keeps
  /// (empty when not kept).
  struct Columns {
    std::vector<float> x, y, z;
    std::vector<std::uint32_t> stamps, ids;
    std::vector<float> intensities, times;
  };

  Motion motion;  ///< frame 0: the tree has taken no frame (and has no root)
  std::vector<NodeEntry> nodes;  ///< empty: no root
  Columns points;
};

/// The parts of `tree`.
TreeParts parts_of(const Tree& tree);

}  // namespace eco::detail
