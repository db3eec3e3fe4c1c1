#pragma once
/// @file ego_octree.hpp
/// The Ego-Centric Octree: an octree of the points inside a cube of side L that travels with the
/// sensor.
///
/// Contract (docs/design.md explains how each part is kept):
/// * Ego box: Box(p) = [p - L/2, p + L/2) per world axis, p the sensor position. Membership is
///   tested on the stored coordinates, so it is exact.
/// * The region R_t (Config::region) is the box itself (`cube`, the default) or a ball or an
///   oriented box about the sensor inside it.
/// * After update() returns, the held points are exactly
///   { p in held(t-1) ∪ inserted(t) : p in Box(p_t) ∩ R_t }, minus density-cap refusals, cleared
///   and aged points.
/// * Queries (knn, radius, box, voxelize) are exact over the held points.
/// * Points are stored as float offsets from a world "precision origin" kept within 2 km of the
///   sensor (moved in steps of 1024 m), so precision does not degrade with distance travelled:
///   a stored coordinate is within 0.25 mm of the double-precision world point.
/// * Per-point attributes (Config::attributes: ids, intensities, times) are stored with their
///   point and come back with every query (Neighbor::attributes, HeldPoint::attributes); an age
///   limit may be given in frames or in seconds (Config::max_age_seconds, read from the times).
/// * Bad input throws std::invalid_argument naming the value, and leaves the tree unchanged.
///   Non-finite scan points are skipped and counted, never thrown on.
///
/// Thread safety:
/// * const calls (the queries of MapReader, stats, save) may run concurrently with each other;
///   update(), update_relative() and snapshot() need exclusive access to the tree;
/// * a Snapshot is immutable: any number of threads may query it at any time, also while its
///   tree runs update() or publishes later snapshots, and any thread may drop the last handle.
/// The library never prints and never aborts.

#include <eco/config.hpp>
#include <eco/map_reader.hpp>
#include <eco/snapshot.hpp>
#include <eco/types.hpp>

#include <Eigen/Geometry>

#include <memory>
#include <string>

namespace eco {

namespace detail {
class Tree;
struct ClearingState;
class DensityCells;
}  // namespace detail

/// The live map. Its queries (knn, radius, box, voxel map, points, stats) are MapReader's.
class EgoOctree final : public MapReader {
 public:
  /// Validates `config` (throws std::invalid_argument) and creates an empty tree.
  explicit EgoOctree(const Config& config = {});
  ~EgoOctree();
  EgoOctree(EgoOctree&&) noexcept;
  EgoOctree& operator=(EgoOctree&&) noexcept;
  EgoOctree(const EgoOctree&) = delete;
  EgoOctree& operator=(const EgoOctree&) = delete;

  /// Advances to the sensor pose `world_T_sensor` (maps sensor-frame points to the world) and
  /// takes in `scan` (sensor frame). Cost grows with what changed this frame, not with what is
  /// held. Throws std::invalid_argument, tree unchanged, if the pose is not finite or its
  /// rotation is not orthonormal.
  const UpdateStats& update(const Eigen::Isometry3d& world_T_sensor, ScanView scan);

  /// The same with the relative motion `previous_T_current` (the new sensor pose expressed in the
  /// previous sensor frame): world_T_sensor(t) = world_T_sensor(t-1) * previous_T_current.
  /// The first frame starts from the identity pose.
  const UpdateStats& update_relative(const Eigen::Isometry3d& previous_T_current, ScanView scan);

  [[nodiscard]] const UpdateStats& last_update() const;

  /// The map as it is now, published for readers on other threads: an immutable handle that
  /// answers every query as this tree does now, names its frame and pose, and never changes
  /// while this tree updates. It costs a reference per page of points (4–16 KiB) and a copy of
  /// the nodes (a tenth of the map's bytes or less), not a copy of the map: the tree copies a
  /// page of points when it first writes it after the call (docs/design.md, "Snapshots").
  /// What only snapshots hold goes back to the system when their last handle goes
  /// (Stats::snapshot_bytes). Needs exclusive access, as update() does.
  [[nodiscard]] std::shared_ptr<const Snapshot> snapshot();

  /// Writes the whole state needed to go on exactly — configuration, pose, precision origin,
  /// frame counter and clock, every held point with its ids and attributes, and free-space
  /// clearing's last range image — to the file `path` (docs/map-format.md). The file is written
  /// beside `path` and renamed over it once whole and flushed to the disk, so a save that fails
  /// (a full disk, no permission) leaves any earlier file at `path` as it was. Throws
  /// std::runtime_error naming the path and the reason. A const call: it may run beside queries.
  void save(const std::string& path) const;
  /// The tree saved at `path`: it answers every query as the saved one did and, fed the same
  /// next frames, stays identical to it (last_update() starts empty). Throws std::runtime_error
  /// naming the path and the byte offset of the first part that does not make a map — a wrong
  /// magic or version, a checksum mismatch, a truncated file, a value out of range — and nothing
  /// is loaded.
  [[nodiscard]] static EgoOctree load(const std::string& path);

 private:
  EgoOctree(std::unique_ptr<detail::Tree> tree, std::unique_ptr<detail::ClearingState> clearing);

  [[nodiscard]] const detail::Tree& held() const override;
  [[nodiscard]] std::size_t bytes_beside_tree() const override;

  std::unique_ptr<detail::Tree> tree_;
  std::unique_ptr<detail::ClearingState> clearing_;  // free-space clearing's, while Config::clearing is on
  std::unique_ptr<detail::DensityCells> density_;    // the density cap's counts, while it is on
  UpdateStats last_update_;
};

}  // namespace eco
