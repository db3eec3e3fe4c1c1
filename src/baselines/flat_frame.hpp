#pragma once
// What the baselines that keep no detail::Tree (scan_pass, nanoflann, pcl_octree) share with ECO,
// so that they take in exactly ECO's points: the pose, the precision origin and the ego box,
// the admission of scan points, and the density cap's cell counts.

#include "core/density/density_cells.hpp"
#include "core/tree/tree.hpp"
#include "update/admission.hpp"
#include "query/queries.hpp"
#include "update/stages.hpp"

#include <optional>
#include <stdexcept>
#include <string>

namespace eco::baselines {

class FlatFrame {
 public:
  /// Throws std::invalid_argument for a bad configuration, an age limit, free-space clearing or
  /// kept attributes (`who` has none of them).
  FlatFrame(const Config& config, const std::string& who) : cfg_(config), density_(config.density_cap) {
    cfg_.validate();
    if (cfg_.max_age_frames > 0) {
      throw std::invalid_argument("the " + who + " baseline has no age limit (max_age_frames = " +
                                  std::to_string(cfg_.max_age_frames) + ")");
    }
    if (cfg_.clearing.enabled) {
      throw std::invalid_argument("the " + who + " baseline has no free-space clearing (clearing.enabled = true)");
    }
    if (cfg_.attributes.any()) {
      throw std::invalid_argument("the " + who + " baseline keeps no per-point attributes (attributes.ids, "
                                  ".intensity or .time = true)");
    }
  }

  /// ECO's preamble and stage 1: checks the arguments, then moves to `pose`. Returns the
  /// frame's statistics, how far held points must move (old origin - new origin) when the
  /// precision origin moved, and the scan's admission.
  struct Step {
    UpdateStats stats;
    std::optional<Eigen::Vector3d> shift;
    detail::Admission admission;
  };
  Step advance(const Eigen::Isometry3d& world_T_sensor, const ScanView& scan) {
    UpdateStats stats = detail::begin_update(cfg_, world_T_sensor, scan);
    motion_ = detail::next_motion(world_T_sensor, motion_, cfg_.box_side);
    density_.enter(motion_);
    if (motion_.origin_shift) density_.clear();  // the caller counts the re-expressed points anew
    return {stats, motion_.origin_shift, detail::admission(motion_, cfg_.insert_policy)};
  }

  /// Calls take(p) for each point of `scan` that `step`'s admission and the density cap admit
  /// (counted in the cap's cells), in scan order: ECO's shift-in, without the tree.
  template <class Take>
  void take_in(ScanView scan, Step& step, Take&& take) {
    step.admission.for_each_group(scan, step.stats, [&](const detail::AdmittedGroup& group) {
      std::array<std::uint8_t, detail::kAdmitGroup> passed;
      step.stats.skipped_by_density += density_.judge(group.points.data(), group.size, passed.data());
      detail::for_each_set(passed.data(), group.size, [&](std::size_t j) { take(group.points[j]); });
    });
  }
  /// Counts a held point (after the origin moved) or forgets one that left.
  void count(const std::array<float, 3>& p) { density_.count(p); }
  void forget(const std::array<float, 3>& p) { density_.forget(p); }

  [[nodiscard]] detail::Box box() const { return motion_.box; }
  [[nodiscard]] std::array<double, 3> local(const Eigen::Vector3d& w) const {
    return {w[0] - anchor()[0], w[1] - anchor()[1], w[2] - anchor()[2]};
  }
  [[nodiscard]] Eigen::Vector3d world(const std::array<float, 3>& p) const { return motion_.to_world(p); }
  /// The closed query box [lo, hi] (world) in the anchor frame.
  [[nodiscard]] detail::Box closed_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
    detail::Box b;
    b.half_open = false;
    b.lo = local(lo);
    b.hi = local(hi);
    return b;
  }
  /// Held point p as a result for query q (anchor frame): world point, squared distance in double.
  [[nodiscard]] Neighbor neighbor(const std::array<double, 3>& q, const std::array<float, 3>& p) const {
    const double dx = double(p[0]) - q[0], dy = double(p[1]) - q[1], dz = double(p[2]) - q[2];
    return {world(p), dx * dx + dy * dy + dz * dz, {}};
  }
  /// Empty when every point of `held` lies in the current ego box, else what is wrong.
  template <class Points>
  [[nodiscard]] std::string outside_box(const Points& held) const {
    if (frames() == 0) return "";
    const detail::Box b = box();
    for (const auto& p : held) {
      if (!b.contains(p[0], p[1], p[2])) return "point outside the ego box";
    }
    return "";
  }
  /// Voxels of side `res` as seen from the stored coordinates (build once per map, not per point).
  [[nodiscard]] detail::WorldGrid voxel_grid(double res) const {
    return detail::WorldGrid({anchor()[0], anchor()[1], anchor()[2]}, res);
  }

  /// Throws std::invalid_argument naming `resolution` unless voxels of that side can be indexed.
  void require_voxel_resolution(double res) const {
    // held points lie within 2048 m + L of the precision origin
    const double reach = anchor().cwiseAbs().maxCoeff() + 2048.0 + 2 * cfg_.box_side;
    if (!(res > 0.0) || !detail::grid_fits(reach, res)) {
      throw std::invalid_argument("voxel_keys: resolution = " + std::to_string(res) +
                                  " m must be > 0 and index points " + std::to_string(reach) +
                                  " m from the world origin in fewer than 2^50 voxels");
    }
  }

  [[nodiscard]] const Config& config() const { return cfg_; }
  [[nodiscard]] const Eigen::Isometry3d& pose() const { return motion_.pose; }
  [[nodiscard]] const Eigen::Vector3d& anchor() const { return motion_.anchor; }
  [[nodiscard]] std::size_t frames() const { return motion_.frame; }
  [[nodiscard]] std::size_t bytes() const { return sizeof(*this) + density_.bytes(); }

 private:
  Config cfg_;
  detail::Motion motion_;  // the current frame's, as ECO's stage 1 finds it
  detail::DensityCells density_;
};

/// Nearest first, as every query reports neighbours.
inline bool nearer(const Neighbor& a, const Neighbor& b) { return a.sq_dist < b.sq_dist; }

/// The voxel of stored point p in `grid`.
inline VoxelKey voxel_key(const detail::WorldGrid& grid, const std::array<float, 3>& p) {
  const auto [x, y, z] = grid.index(p);
  return {x, y, z};
}

/// Sorted unique voxel keys of points `held` (anchor frame) at `res`: the brute-force voxel map.
template <class Points>
std::vector<VoxelKey> voxel_keys_of_points(const FlatFrame& frame, const Points& held, double res) {
  frame.require_voxel_resolution(res);
  const detail::WorldGrid grid = frame.voxel_grid(res);
  std::vector<VoxelKey> keys;
  keys.reserve(held.size());
  for (const auto& p : held) keys.push_back(voxel_key(grid, {p[0], p[1], p[2]}));
  detail::sort_unique(keys);
  return keys;
}

}  // namespace eco::baselines
