#pragma once
/// @file map_reader.hpp
/// The queries a held map answers: the live EgoOctree's and a Snapshot's, with the same names,
/// arguments and results.

#include <eco/config.hpp>
#include <eco/query_threads.hpp>
#include <eco/types.hpp>

#include <Eigen/Geometry>

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace eco {

namespace detail {
class Tree;
}  // namespace detail

class MapReader {
 public:
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
  /// A batch, as a registration loop asks it: the k nearest held points to each of `queries`,
  /// query i's nearest first in out[i * k, i * k + found[i]) (found[i] = min(k, size())), the
  /// answers the one-query call gives. `threads` (the calling thread one of them, started for the
  /// call) take the queries 64 at a time as they finish; nothing is allocated per query. Throws
  /// std::invalid_argument naming the value, before any query runs, unless k >= 1, threads >= 1,
  /// out.size() == queries.size() * k, found.size() == queries.size() and every query is finite.
  void knn(std::span<const Eigen::Vector3d> queries, std::size_t k, std::span<Neighbor> out,
           std::span<std::size_t> found, unsigned threads = 1, Frame frame = Frame::World) const;
  /// The same batch on threads kept between calls (query_threads.hpp): what a loop asking a
  /// batch many times a second wants, as starting threads each call costs a call's tenth.
  void knn(std::span<const Eigen::Vector3d> queries, std::size_t k, std::span<Neighbor> out,
           std::span<std::size_t> found, QueryThreads& threads, Frame frame = Frame::World) const;

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

  /// Held points inside the closed box [lo, hi] of the axes `box_pose` (rigid) places in `frame`,
  /// returned in `frame`: a box turned any way — what lies up to 2 m ahead of the bumper is
  /// oriented_box(sensor_T_bumper, {0, -1, -0.5}, {2, 1, 1.5}, Frame::Sensor). box(lo, hi,
  /// Frame::Sensor) is the box in the sensor's own axes. Subtrees wholly inside are taken whole,
  /// wholly outside skipped; the others tested point by point.
  [[nodiscard]] std::vector<Eigen::Vector3d> oriented_box(const Eigen::Isometry3d& box_pose, const Eigen::Vector3d& lo,
                                                          const Eigen::Vector3d& hi, Frame frame = Frame::World) const;
  /// The same points with their attributes.
  [[nodiscard]] std::vector<HeldPoint> oriented_box_with_attributes(const Eigen::Isometry3d& box_pose,
                                                                    const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
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
  /// Every held point as float32 x, y, z, in world axes less `origin` (each float the world
  /// coordinate in double, less origin's, rounded once), 3 floats a point into `xyz`, in points()'
  /// order: the bulk copy a viewer or a ROS message takes, a leaf's block at a time. Throws
  /// std::invalid_argument unless `xyz` holds 3 × size() floats.
  void copy_points(std::span<float> xyz, const Eigen::Vector3d& origin = Eigen::Vector3d::Zero()) const;

  [[nodiscard]] std::size_t size() const;  ///< points held, O(1)
  [[nodiscard]] Stats stats() const;       ///< O(nodes)
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

  /// Checks every structural invariant (bounds, counts, cells, parent links); returns an empty
  /// string when all hold, else a description of the first violation. O(points); for tests and
  /// for users who want to check a map.
  [[nodiscard]] std::string check_invariants() const;

 protected:
  MapReader() = default;
  MapReader(const MapReader&) = default;
  MapReader(MapReader&&) noexcept = default;
  MapReader& operator=(const MapReader&) = default;
  MapReader& operator=(MapReader&&) noexcept = default;
  ~MapReader() = default;

 private:
  /// The tree the queries read.
  [[nodiscard]] virtual const detail::Tree& held() const = 0;
  /// Bytes held beside the tree (free-space clearing's), counted in stats().
  [[nodiscard]] virtual std::size_t bytes_beside_tree() const { return 0; }
};

}  // namespace eco
