#pragma once
// The density cap's state: how many held points each cell of the cap's world grid holds, on the
// current frame's grid. Its owner (EgoOctree, a baseline) hands it to the update's stages, which
// tell it the frame and the points that arrive (judge), leave (forget) or are counted anew
// (recount); the counts agree with the held points as long as every point that leaves is forgotten.

#include "core/density/cell_counts.hpp"
#include "core/density/density_gate.hpp"
#include "core/geometry/geometry.hpp"
#include "core/geometry/motion.hpp"

#include <eco/config.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>

namespace eco::detail {

class DensityCells {
 public:
  explicit DensityCells(const DensityCap& cap) : cap_(cap), counts_(cap.max_points) {}

  [[nodiscard]] bool enabled() const { return cap_.enabled(); }
  /// Enters the frame of `motion`: the cap's cells from its anchor (the counts stay; after the
  /// precision origin moved, recount).
  void enter(const Motion& motion) { grid_ = ego_grid(motion, cap_); }

  /// The cap's verdicts on new points[0, n) (n <= kDensityGroup), in their order: passed[i] = 1
  /// when point i's cell held fewer than the cap, and it is counted there. Returns how many it
  /// refused; while the cap is off every point passes, counted nowhere.
  std::size_t judge(const std::array<float, 3>* points, std::size_t n, std::uint8_t* passed) {
    return judge_group(counts_, grid_, cap_, points, n, passed);
  }
  /// Counts a held point whatever its cell holds, or forgets one that left.
  void count(const std::array<float, 3>& p) {
    if (enabled()) counts_.add(key(p));
  }
  void forget(const std::array<float, 3>& p) {
    if (enabled()) counts_.remove(key(p));
  }
  /// Forgets every point produce(offer) offers, a group at a time.
  template <class Produce>
  void forget_all(Produce&& produce) {
    if (enabled()) forget_in_groups(counts_, grid_, produce);
  }
  /// Counts anew the points produce(add) adds, forgetting all others (a map whose keys moved with
  /// the precision origin, a map loaded).
  template <class Produce>
  void recount(Produce&& produce) {
    counts_.clear();
    if (enabled()) count_in_groups(counts_, grid_, produce);
  }
  void clear() { counts_.clear(); }
  [[nodiscard]] std::size_t bytes() const { return counts_.bytes(); }

 private:
  [[nodiscard]] std::uint64_t key(const std::array<float, 3>& p) const { return CellCounts::key(grid_.index(p)); }

  DensityCap cap_;
  CellCounts counts_;
  WorldGrid grid_{{0, 0, 0}, 1.0};
};

/// The counts for `config`'s cap; null while it is off.
inline std::unique_ptr<DensityCells> density_cells_for(const Config& config) {
  return config.density_cap.enabled() ? std::make_unique<DensityCells>(config.density_cap) : nullptr;
}

}  // namespace eco::detail
