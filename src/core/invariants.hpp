#pragma once
// Every structural promise of a tree, checked from scratch (EgoOctree::check_invariants).

#include "core/tree.hpp"

#include <string>

namespace eco::detail {

/// Empty when every structural invariant holds, else the first violation.
std::string check_tree(const Tree& t);

}  // namespace eco::detail
