#pragma once
/// @file ego_octree.hpp
/// The Ego-Centric Octree: an octree of the points inside a cube of side L that travels with the
/// sensor.
///
/// Contract (see docs/DESIGN.md §1):
/// * Ego box: Box(p) = [p - L/2, p + L/2) per world axis, p the sensor position. Membership is
///   tested on the stored coordinates, so it is exact.
/// * After update() returns, the held points are exactly
///   { p in held(t-1) ∪ inserted(t) : p in Box(p_t) }, minus density-cap refusals and aged points.
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
/// Thread safety: concurrent const calls (queries, stats) are safe; update() needs exclusive
/// access. The library never prints and never aborts.

#include <eco/config.hpp>
#include <eco/types.hpp>

#include <Eigen/Geometry>

#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace eco {

namespace detail {
class Tree;
struct ClearingState;
}  // namespace detail

class EgoOctree {
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

  /// The k nearest held points to `query`, nearest first. Fewer than k when fewer are held.
  [[nodiscard]] std::vector<Neighbor> knn(const Eigen::Vector3d& query, std::size_t k,
                                          Frame frame = Frame::World) const;
  /// Caller-owned buffer variant: writes at most out.size() neighbours, returns how many.
  std::size_t knn(const Eigen::Vector3d& query, std::span<Neighbor> out,
                  Frame frame = Frame::World) const;
  /// The same as ids and squared distances, nanoflann's way: writes the ids of at most
  /// ids.size() nearest points and their squared distances, nearest first, into the caller's
  /// buffers (no allocation); returns how many. Throws std::invalid_argument unless
  /// Config::attributes.ids is on and the two spans have the same size.
  std::size_t knn(const Eigen::Vector3d& query, std::span<std::uint32_t> ids, std::span<double> sq_dists,
                  Frame frame = Frame::World) const;

  /// Held points with ||p - query|| <= radius (a plain radius in metres, not squared),
  /// nearest first.
  [[nodiscard]] std::vector<Neighbor> radius(const Eigen::Vector3d& query, double radius,
                                             Frame frame = Frame::World) const;

  /// Held points inside the closed box [lo, hi], in no particular order.
  [[nodiscard]] std::vector<Eigen::Vector3d> box(const Eigen::Vector3d& lo,
                                                 const Eigen::Vector3d& hi,
                                                 Frame frame = Frame::World) const;

  /// The same points with their attributes.
  [[nodiscard]] std::vector<HeldPoint> box_with_attributes(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                                                           Frame frame = Frame::World) const;

  /// Keys of the occupied voxels of the world-aligned grid of side `resolution` [m], unique, in no
  /// particular order (sort them if you need one). Voxel i on an axis holds the stored coordinate
  /// f (offset from the precision origin o) with i*res - o <= f < (i+1)*res - o, walls in double.
  /// Every key holds at least one point, so every voxel meets the ego box. With
  /// resolution = Config::voxel_size * 2^i (Quantised mode) the map visits one node per voxel,
  /// not every point. Throws std::invalid_argument naming `resolution` if it is not > 0 or too
  /// small to index the held points in 64 bits.
  [[nodiscard]] std::vector<VoxelKey> voxel_keys(double resolution) const;
  /// Centres of the same voxels, in `frame`, in the same order.
  [[nodiscard]] std::vector<Eigen::Vector3d> voxelize(double resolution,
                                                      Frame frame = Frame::World) const;

  /// Every held point, in world coordinates, in no particular order.
  [[nodiscard]] std::vector<Eigen::Vector3d> points() const;
  /// Every held point with its attributes, world coordinates, in no particular order.
  [[nodiscard]] std::vector<HeldPoint> points_with_attributes() const;
  /// Calls `visit` once per held point with its world coordinates.
  void for_each_point(const std::function<void(const Eigen::Vector3d&)>& visit) const;

  [[nodiscard]] std::size_t size() const;  ///< points held, O(1)
  [[nodiscard]] Stats stats() const;       ///< O(nodes)
  [[nodiscard]] const UpdateStats& last_update() const;
  [[nodiscard]] const Config& config() const;

  /// The current sensor pose (identity before the first update).
  [[nodiscard]] const Eigen::Isometry3d& pose() const;
  /// The current ego box [lo, hi) in world coordinates (empty before the first update).
  [[nodiscard]] Eigen::AlignedBox3d ego_box() const;
  /// The world point that stored float coordinates are offsets from (a multiple of 1024 m).
  [[nodiscard]] Eigen::Vector3d precision_origin() const;
  /// The time [s] that stored times are offsets from (Config::attributes.time; a multiple of
  /// 64 s within 128 s of the latest time taken in; 0 before any).
  [[nodiscard]] double time_origin() const;
  /// Updates taken so far.
  [[nodiscard]] std::uint32_t frame_count() const;

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

  /// Checks every structural invariant (bounds, counts, cells, parent links); returns an empty
  /// string when all hold, else a description of the first violation. O(points); for tests and
  /// for users who want to check a map.
  [[nodiscard]] std::string check_invariants() const;

 private:
  EgoOctree(std::unique_ptr<detail::Tree> tree, std::unique_ptr<detail::ClearingState> clearing);

  std::unique_ptr<detail::Tree> tree_;
  std::unique_ptr<detail::ClearingState> clearing_;  // free-space clearing's, while Config::clearing is on
  UpdateStats last_update_;
};

}  // namespace eco
