#pragma once
// Free-space clearing's arrivals (FreeSpaceClearing::arrivals): a point that comes in where the
// scan before its own saw empty space is something that moved in. Insertion judges each new point
// against that scan (ArrivalCheck); those it sees through are held for one update, then leave the
// tree (release_arrivals, src/update/stages.hpp).

#include "core/tree.hpp"
#include "update/pixel_lookup.hpp"
#include "update/scan_judge.hpp"

#include <span>
#include <vector>

namespace eco::detail {

/// Notes, of the points an update brings in, those the last update's scan sees through (from
/// where it was taken), in the tree's list of points to leave at the next update.
class ArrivalCheck {
 public:
  /// `before`: the last update's scan, kept by `tree`; `motion`: this update's.
  ArrivalCheck(Tree& tree, const Motion& motion, const Tree::KeptImage& before);
  /// Judges `batch`, new points about to be inserted (StoredPoints or BarePoints).
  template <class Point>
  void operator()(std::span<const Point> batch);

 private:
  PixelLookup pixels_;
  Judge judge_;
  std::vector<StoredPoint>& leaving_;
};

}  // namespace eco::detail
