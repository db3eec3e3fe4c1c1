#pragma once
/// @file config.hpp
/// The one configuration struct of an EgoOctree. Every field has a unit, a default and a typical
/// range; `validate()` is called once by the EgoOctree constructor and throws
/// `std::invalid_argument` naming the offending field and value.

#include <cstdint>

namespace eco {

/// How the root cell follows the sensor.
enum class Recentring {
  /// The root centre moves in whole steps of the quantum q = L / (2^k - 1); cells at depth >= k sit
  /// on a fixed world lattice, so re-centring only re-links the top k levels. Default.
  Quantised,
  /// The root is re-centred exactly on the sensor every frame (the paper's algorithm): subtrees
  /// whose bounds no longer fit their moved octant are rebuilt from their points.
  Exact,
};

/// Which scan points an update inserts.
enum class InsertPolicy {
  /// Only points in R_in = Box(p_t) \ Box(p_{t-1}) (the paper's policy; right for a static,
  /// pre-aggregated map streamed by pose).
  ShiftInOnly,
  /// Every scan point inside Box(p_t) (right for raw scans; pair it with a density cap or an age
  /// limit to bound memory while the sensor stands still).
  AllInBox,
};

/// Optional cap on points per world-aligned cell: at most `max_points` points are held in any cell
/// [i*cell_size, (i+1)*cell_size)^3 (walls in double: see EgoOctree::voxel_keys). A new point that
/// would exceed the cap is not inserted (the points already held are kept). Off while
/// `max_points == 0`. Counts are kept per cell as points come and go, so the test is O(1).
struct DensityCap {
  double cell_size = 0.0;    ///< [m] side of the density cell; typical 0.05–0.5; in (box_side / 262142, box_side].
  std::uint32_t max_points = 0;  ///< points per cell; 0 = cap off, typical 1–10, at most 1023.

  [[nodiscard]] bool enabled() const { return max_points > 0; }
};

/// Configuration of an EgoOctree.
struct Config {
  double box_side = 20.0;  ///< L [m]: side of the ego cube held around the sensor; typical 10–100.
  std::uint32_t leaf_capacity = 32;  ///< N_max: a leaf with more points splits; typical 8–64.
  double min_cell_size = 0.05;  ///< [m] cells are never split below this side; typical 0.01–0.5.
  Recentring recentring = Recentring::Quantised;  ///< see Recentring.
  std::uint32_t quantum_levels = 3;  ///< k, Quantised only: q = L / (2^k - 1); range 1–5.
  /// see InsertPolicy: every scan point in the box by default (raw scans); the paper's
  /// ShiftInOnly suits a pre-aggregated map.
  InsertPolicy insert_policy = InsertPolicy::AllInBox;
  DensityCap density_cap{};  ///< optional, off by default.
  std::uint32_t max_age_frames = 0;  ///< drop points inserted more than this many frames ago; 0 = off.
  /// [m] Quantised only: the voxel size you will ask voxel maps at. The quantum is rounded up to
  /// voxel_size * 2^j, so cells of depth >= k are world voxels of side voxel_size * 2^i and
  /// voxel_keys(voxel_size * 2^i) walks nodes instead of points. 0 = the paper's quantum
  /// L / (2^k - 1); at most box_side.
  double voxel_size = 0.1;

  /// Throws std::invalid_argument naming the field and value when the configuration is unusable.
  void validate() const;

  /// The re-centring quantum [m]: q = L / (2^k - 1) (widened by 1e-9 relative, so the box stays
  /// strictly inside the root cell under rounding), rounded up to voxel_size * 2^j when
  /// voxel_size > 0; 0 in Exact mode.
  [[nodiscard]] double quantum() const;
  /// Side [m] of the root cell: L in Exact mode, q * 2^k (>= L + q) in Quantised mode.
  [[nodiscard]] double root_side() const;
  /// The deepest level a cell may reach: the largest d with root_side / 2^d >= min_cell_size.
  [[nodiscard]] int max_depth() const;
};

}  // namespace eco
