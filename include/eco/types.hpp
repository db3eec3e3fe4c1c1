#pragma once
/// @file types.hpp
/// Plain value types of the ECO API: scan views, query frames, results and statistics.

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace eco {

/// A read-only view of a scan: `count` points of three floats (x, y, z, in metres, sensor frame),
/// `stride` floats apart. Works over `Eigen::Vector3f` arrays, packed N x 3 arrays, and KITTI's
/// N x 4 (x, y, z, reflectance) records alike. The caller owns the memory for the call's duration.
///
/// Per-point attributes, each null or `count` entries, point i's at index i: the tree stores those
/// Config::attributes keeps (a kept one must be given) and ignores the others.
struct ScanView {
  const float* data = nullptr;
  std::size_t count = 0;
  std::size_t stride = 3;  ///< floats from one point to the next (>= 3)
  const std::uint32_t* ids = nullptr;  ///< the caller's id of each point (an index, a label, ...)
  const float* intensities = nullptr;  ///< intensity or reflectance, any finite or non-finite float
  const double* times = nullptr;       ///< [s] when each point was measured; finite and >= 0

  ScanView() = default;
  ScanView(const float* points, std::size_t n, std::size_t stride_floats = 3)
      : data(points), count(n), stride(stride_floats) {}
  ScanView(const std::vector<Eigen::Vector3f>& points)  // NOLINT: implicit on purpose
      : data(points.empty() ? nullptr : points.front().data()), count(points.size()), stride(3) {}

  [[nodiscard]] Eigen::Vector3f operator[](std::size_t i) const {
    const float* p = data + i * stride;
    return {p[0], p[1], p[2]};
  }
};

/// The frame in which query points are given and results returned.
enum class Frame {
  World,   ///< the fixed world frame of the poses
  Ego,     ///< world axes, origin at the current sensor position (the paper's F_eco,t)
  Sensor,  ///< the sensor's own frame: origin at the sensor, axes turned with it (REP 103: x forward)
};

/// What a held point carries besides its position (ScanView's attributes): zero where
/// Config::attributes does not keep one. `time` comes back as stored (see Config::attributes).
struct PointAttributes {
  std::uint32_t id = 0;
  float intensity = 0.0f;
  double time = 0.0;  ///< [s]
  friend bool operator==(const PointAttributes&, const PointAttributes&) = default;
};

/// One k-nearest-neighbour or radius result.
struct Neighbor {
  Eigen::Vector3d point;  ///< in the frame of the query
  double sq_dist = 0.0;   ///< squared Euclidean distance [m^2]
  PointAttributes attributes;
};

/// A held point with its attributes (box and whole-map results).
struct HeldPoint {
  Eigen::Vector3d point;  ///< in the frame asked for
  PointAttributes attributes;
};

/// Integer index of a world-aligned voxel: voxel i spans [i*res, (i+1)*res) per axis.
struct VoxelKey {
  std::int64_t x = 0, y = 0, z = 0;
  friend bool operator==(const VoxelKey&, const VoxelKey&) = default;
  friend auto operator<=>(const VoxelKey&, const VoxelKey&) = default;
};

/// The world-aligned voxel of side `side` holding `p` (any vector with x(), y(), z()).
template <class Vector>
[[nodiscard]] VoxelKey voxel_of(const Vector& p, double side) {
  return {std::int64_t(std::floor(double(p.x()) / side)), std::int64_t(std::floor(double(p.y()) / side)),
          std::int64_t(std::floor(double(p.z()) / side))};
}

/// What the tree holds now. Computed by a walk over the nodes: O(nodes).
struct Stats {
  std::size_t points = 0;        ///< points held
  std::size_t nodes = 0;         ///< live nodes, inner and leaf
  std::size_t leaves = 0;        ///< live leaves holding at least one point
  double mean_leaf_depth = 0.0;  ///< over non-empty leaves, weighted equally
  int max_leaf_depth = 0;
  std::size_t bytes = 0;         ///< every byte the tree's pools reserve, free slots included
  /// Bytes only snapshots keep alive: the versions of pages the tree has replaced since it
  /// published them (EgoOctree::snapshot()), given back when the last snapshot holding them goes.
  /// The same figure from the tree and from any of its snapshots.
  std::size_t snapshot_bytes = 0;
};

/// The region held after an update: Config::region as its lookahead grew it and its budget
/// scaled it; zeros for the cube.
struct RegionExtents {
  double radius = 0.0;  ///< [m] a ball's
  double ahead = 0.0, behind = 0.0, left = 0.0, right = 0.0, up = 0.0, down = 0.0;  ///< [m] an oriented box's
  double scale = 1.0;   ///< the budget's scale about the sensor (1: the whole region)
  double speed = 0.0;   ///< [m/s] the smoothed speed the lookahead follows
};

/// What the last update did.
struct UpdateStats {
  std::size_t scan_points = 0;        ///< points in the scan given
  std::size_t inserted = 0;           ///< scan points now held
  std::size_t skipped_nonfinite = 0;  ///< scan points with a NaN or infinite coordinate
  std::size_t skipped_by_policy = 0;  ///< finite scan points outside Box(p_t) (or outside R_in)
  std::size_t skipped_by_density = 0; ///< scan points refused by the density cap
  std::size_t pruned = 0;             ///< held points that left the box or the region (R_out)
  std::size_t region_tested = 0;      ///< held points tested one by one for the region's surface alone
  std::size_t skipped_by_age = 0;     ///< scan points already older than max_age_seconds
  std::size_t aged_out = 0;           ///< held points dropped by the age limit
  std::size_t cleared = 0;            ///< held points the scan saw through (free-space clearing)
  std::size_t relinked_subtrees = 0;  ///< subtrees kept whole and attached to a new parent
  std::size_t rebuilt_subtrees = 0;   ///< subtrees dissolved and their points re-inserted
  std::size_t reinserted_points = 0;  ///< points moved by those rebuilds
  bool rebased = false;               ///< the precision origin moved this frame (see EgoOctree)
  std::size_t over_budget = 0;        ///< held points the budget's shrinking region let go
  RegionExtents region;               ///< the region held after this update
};

}  // namespace eco

/// Voxel keys in unordered containers (a voxel map, a downsampling grid).
template <>
struct std::hash<eco::VoxelKey> {
  std::size_t operator()(const eco::VoxelKey& k) const noexcept {
    // the three large primes of Teschner et al. (2003), the spatial hash most voxel maps use
    return std::size_t(k.x * 73856093) ^ std::size_t(k.y * 19349663) ^ std::size_t(k.z * 83492791);
  }
};
