#pragma once
/// @file local_map.hpp
/// The map a LiDAR odometry registers each scan against, behind one small interface so that the
/// map is the only thing that varies between runs (Odometry, odometry.hpp):
///
/// | name         | what it is                                                                      |
/// |--------------|---------------------------------------------------------------------------------|
/// | `eco`        | an EgoOctree; its density cap is the map's downsampling                         |
/// | `voxel_hash` | a voxel-hash map as KISS-ICP keeps it: at most N points a voxel, neighbours searched in the 27 voxels around the query (approximate) |
/// | `nanoflann`  | a nanoflann k-d tree rebuilt every frame over the same capped set of points     |
/// | `pcl_octree` | PCL's OctreePointCloudSearch kept incrementally over the same capped set        |
///
/// The last two are the benchmark's baselines, made by make_any_local_map (src/odometry/baseline_maps.hpp).
///
/// Every map holds the points of the ego cube of side `box_side` around the sensor, at most
/// `max_points` per world-aligned cell of side `cell_size` (the first to arrive are kept).

#include <eco/types.hpp>

#include <Eigen/Geometry>

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace eco::odometry {

struct MapSettings {
  double box_side = 200.0;       ///< [m] side of the cube held around the sensor
  double cell_size = 1.0;        ///< [m] side of the density cell (the voxel-hash map's voxel)
  std::uint32_t max_points = 20; ///< points kept per cell
  unsigned threads = 1;          ///< threads a batch of queries is spread over (ECO's batch KNN)
  /// [m] `eco_ball`'s region: a ball this wide about the sensor inside the cube (KISS-ICP's map
  /// keeps its max_range); past box_side / 2, the cube's half side.
  double ball_radius = 100.0;

  /// Throws std::invalid_argument naming the first value out of range.
  void validate() const;
};

class LocalMap {
 public:
  virtual ~LocalMap() = default;

  [[nodiscard]] virtual std::string name() const = 0;
  /// False when a query may miss a nearer held point (voxel_hash: it searches 27 voxels only).
  [[nodiscard]] virtual bool exact() const { return true; }
  /// Moves to `world_T_sensor`, drops what left the cube, and takes in `scan` (sensor frame).
  virtual void update(const Eigen::Isometry3d& world_T_sensor, ScanView scan) = 0;
  /// For every query i (world frame), its at most k nearest held points, nearest first, in
  /// out[i * k, i * k + found[i]). out.size() == queries.size() * k, found.size() == queries.size().
  virtual void knn(std::span<const Eigen::Vector3d> queries, std::size_t k, std::span<Neighbor> out,
                   std::span<std::size_t> found) const = 0;
  [[nodiscard]] virtual std::size_t size() const = 0;
  /// Every held point, world frame, in no particular order.
  [[nodiscard]] virtual std::vector<Eigen::Vector3d> points() const = 0;
};

/// Every name make_local_map accepts: eco, voxel_hash.
[[nodiscard]] const std::vector<std::string>& local_map_names();

/// The map called `name` under `settings`. Throws std::invalid_argument for an unknown name
/// (listing the known ones) or settings out of range.
[[nodiscard]] std::unique_ptr<LocalMap> make_local_map(std::string_view name, const MapSettings& settings);

}  // namespace eco::odometry
