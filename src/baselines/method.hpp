#pragma once
/// @file method.hpp
/// The methods the benchmark compares (docs/benchmarks.md), behind one interface so every method sees
/// the same stream and answers the same queries:
///
/// | name             | update strategy                                                         |
/// |------------------|-------------------------------------------------------------------------|
/// | `eco`            | EgoOctree, quantised re-centring (ours)                                 |
/// | `eco_exact`      | EgoOctree, exact re-centring (the paper's algorithm)                    |
/// | `eco_clearing`   | `eco` with free-space clearing on, whatever the Config says             |
/// | `octree_base`    | bulk rebuild (top-down partition) from the points in the box, every frame |
/// | `ioctree_global` | global-rooted incremental octree (i-Octree): grows its root, never deletes |
/// | `ioctree_target` | the same, bounded: deletes what left the box, inserts what ECO inserts  |
/// | `nanoflann`      | a nanoflann k-d tree over the points in the box, rebuilt every frame    |
/// | `pcl_octree`     | PCL 1.13's OctreePointCloudSearch, kept incrementally (voxel leaves)    |
/// | `scan_pass`      | transform, box test and copy of the scan, no structure: the update's floor |
/// | `scan_only`      | octree_base rebuilt from the current scan alone (the paper's dynamic reference) |
///
/// All hold points the way ECO does (float offsets from a precision origin) and take in the same
/// scan points (the Config's insert policy), so their held sets are equal — except
/// `ioctree_global`, which also keeps everything that left the box, and `eco_clearing`, which
/// drops what the scans show to be free space. The octree baselines share
/// ECO's node layout and query code, so the benchmark compares update strategies, not two
/// implementations of KNN. Queries are in the world frame.

#include <eco/config.hpp>
#include <eco/ego_octree.hpp>
#include <eco/types.hpp>

#include <Eigen/Geometry>

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace eco::baselines {

class Method {
 public:
  virtual ~Method() = default;

  [[nodiscard]] virtual std::string name() const = 0;
  /// False when queries scan every held point (scan_pass): the benchmark does not time them.
  [[nodiscard]] virtual bool indexed() const { return true; }
  /// Advances to `world_T_sensor` and takes in `scan` (sensor frame), as EgoOctree::update.
  /// Throws std::invalid_argument for a pose that is not finite or not rigid.
  virtual void update(const Eigen::Isometry3d& world_T_sensor, ScanView scan) = 0;

  /// Exact k nearest held points, nearest first: writes at most out.size(), returns how many.
  virtual std::size_t knn(const Eigen::Vector3d& query, std::span<Neighbor> out) const = 0;
  [[nodiscard]] std::vector<Neighbor> knn(const Eigen::Vector3d& query, std::size_t k) const;
  /// Held points within `radius` of `query`, nearest first.
  [[nodiscard]] virtual std::vector<Neighbor> radius(const Eigen::Vector3d& query, double radius) const = 0;
  /// Held points in the closed box [lo, hi].
  [[nodiscard]] virtual std::vector<Eigen::Vector3d> box(const Eigen::Vector3d& lo,
                                                         const Eigen::Vector3d& hi) const = 0;
  /// Sorted unique keys of the voxels of side `resolution` that hold a point.
  [[nodiscard]] virtual std::vector<VoxelKey> voxel_keys(double resolution) const = 0;
  /// Every held point, world frame, in no particular order.
  [[nodiscard]] virtual std::vector<Eigen::Vector3d> points() const = 0;

  [[nodiscard]] virtual std::size_t size() const = 0;
  /// Points, nodes, leaf depths (0 where the structure has no leaves to speak of) and bytes.
  [[nodiscard]] virtual Stats stats() const = 0;
  /// The world point stored coordinates are float offsets from.
  [[nodiscard]] virtual Eigen::Vector3d precision_origin() const = 0;
  /// Empty when the structure's invariants hold, else the first violation.
  [[nodiscard]] virtual std::string check_invariants() const = 0;
  [[nodiscard]] virtual const Config& config() const = 0;
  [[nodiscard]] virtual const Eigen::Isometry3d& pose() const = 0;
  /// The EgoOctree behind the method, for what only ECO offers (a map file); null for the others.
  [[nodiscard]] virtual const EgoOctree* ego_octree() const { return nullptr; }
};

/// Every method name make_method accepts, ECO's first.
[[nodiscard]] const std::vector<std::string>& method_names();

/// The method called `name` with `config` (L, N_max, insert policy, ...). Throws
/// std::invalid_argument for an unknown name (listing the known ones) or a configuration the
/// method cannot honour (`nanoflann`, `pcl_octree` and `scan_pass` have no age limit and no
/// free-space clearing; `scan_pass` ignores the density cap). The octrees honour clearing
/// (Config::clearing) through ECO's stage; `scan_only` has nothing to clear.
[[nodiscard]] std::unique_ptr<Method> make_method(std::string_view name, const Config& config);

}  // namespace eco::baselines
