#pragma once
/// @file static_map.hpp
/// The paper's static map: every scan of a sequence placed in the world with its pose and
/// voxel-downsampled, held with a spatial index so the points inside a box are found without
/// looking at the rest of the map.

#include <eco/workloads/workload.hpp>

#include <Eigen/Geometry>

#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

namespace eco::workloads {

class StaticMap {
 public:
  /// Aggregates every frame of `scans` into the world and keeps one point per occupied voxel of
  /// side `resolution` (the centroid of the points that fell in it, as PCL's VoxelGrid does).
  /// Reads one frame at a time. Throws std::invalid_argument for a resolution that is not
  /// positive and finite, or too fine for the map's extent (over 2^20 voxels along an axis
  /// either side of the origin).
  static StaticMap aggregate(const Workload& scans, double resolution);

  /// A map of given world points, indexed in buckets of side `bucket` metres.
  explicit StaticMap(std::vector<Eigen::Vector3d> points, double bucket = 2.0);

  [[nodiscard]] std::size_t size() const { return points_.size(); }
  /// World points, grouped by bucket.
  [[nodiscard]] const std::vector<Eigen::Vector3d>& points() const { return points_; }

  /// Calls visit(point) for every point in the half-open box [lo, hi): O(buckets + points
  /// in the buckets the box touches).
  void for_each_in_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                       const std::function<void(const Eigen::Vector3d&)>& visit) const;

 private:
  [[nodiscard]] std::uint64_t bucket_key(const Eigen::Vector3d& p) const;

  std::vector<Eigen::Vector3d> points_;
  double bucket_;
  std::unordered_map<std::uint64_t, std::pair<std::size_t, std::size_t>> buckets_;  // [begin, end)
};

}  // namespace eco::workloads
