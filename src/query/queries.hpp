#pragma once
// The queries over a tree, as free functions: EgoOctree forwards to them, and the benchmark's
// tree-based baselines (src/baselines) answer with the very same code.

#include "core/tree/tree.hpp"

#include <eco/types.hpp>

#include <functional>
#include <span>
#include <string>
#include <vector>

namespace eco::detail {

/// The nearest held points to `query`, nearest first; writes at most out.size(), returns how many.
std::size_t knn_query(const Tree& t, const Eigen::Vector3d& query, std::span<Neighbor> out, Frame frame);
/// The same as ids and squared distances (ids must be kept; the spans of equal size).
std::size_t knn_ids_query(const Tree& t, const Eigen::Vector3d& query, std::span<std::uint32_t> ids,
                          std::span<double> sq_dists, Frame frame);
/// Held points within `radius` of `query`, nearest first.
std::vector<Neighbor> radius_query(const Tree& t, const Eigen::Vector3d& query, double radius, Frame frame);
/// Held points in the closed box [lo, hi] of the axes `box_pose` places in `frame`, in no
/// particular order.
std::vector<Eigen::Vector3d> box_query(const Tree& t, const Eigen::Isometry3d& box_pose, const Eigen::Vector3d& lo,
                                       const Eigen::Vector3d& hi, Frame frame);
/// The same with their attributes.
std::vector<HeldPoint> box_held_query(const Tree& t, const Eigen::Isometry3d& box_pose, const Eigen::Vector3d& lo,
                                      const Eigen::Vector3d& hi, Frame frame);
/// Unique keys of the occupied voxels of side `resolution`, in no particular order.
std::vector<VoxelKey> voxel_keys_of(const Tree& t, double resolution);
/// Sorts keys[from, end) and drops the repeats there.
void sort_unique(std::vector<VoxelKey>& keys, std::size_t from = 0);
/// Calls visit(world point) once per held point.
void for_each_held(const Tree& t, const std::function<void(const Eigen::Vector3d&)>& visit);
/// Writes each held point (for_each_held's order) as float(world - origin) to out[3i..3i+2].
void copy_held(const Tree& t, const Eigen::Vector3d& origin, float* out);
/// Every held point with its attributes, world frame.
std::vector<HeldPoint> held_points(const Tree& t);
/// Points, nodes, leaf depths and bytes: a walk over the nodes.
Stats tree_stats(const Tree& t);

}  // namespace eco::detail
