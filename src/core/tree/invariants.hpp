#pragma once
// Every structural promise of a tree, checked from scratch (EgoOctree::check_invariants).

#include "core/tree/tree.hpp"

#include <string>

namespace eco::detail {

/// Empty when every structural invariant holds, else the first violation. `in_box`: every
/// held point lies in the current ego box (false for a map that keeps what the sensor left).
std::string check_tree(const Tree& t, bool in_box = true);

}  // namespace eco::detail
