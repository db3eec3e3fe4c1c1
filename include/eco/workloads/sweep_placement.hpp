#pragma once
/// @file sweep_placement.hpp
/// A sweep's points placed by the poses the sensor had while it swept: each point, seen at its own
/// time, moved into the sensor's frame at the cloud's stamp. What a recording with a pose stream
/// (a TUM file, a pose topic, tf) and per-point times gives: the scan without its motion smear.
/// `eco run --data` and `eco_node` place a cloud's points the same way.

#include <eco/workloads/workload.hpp>

#include <Eigen/Geometry>

#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace eco::workloads {

/// The sensor's pose in the world at a time [s]; nullopt where the poses known do not reach.
using PoseAtTime = std::function<std::optional<Eigen::Isometry3d>(double)>;

/// Moves point i, seen at `stamp + times[i]`, into the sensor's frame at `stamp`, the sensor's pose
/// being `pose_at` at each time (sampled 65 times across the sweep, interpolated between: a pose
/// stream is itself interpolated, and one lookup a point would cost more than the update). Points
/// whose time `pose_at` does not reach stay as seen; returns their count.
std::size_t place_at_stamp(std::vector<Eigen::Vector3f>& points, std::span<const double> times, double stamp,
                           const PoseAtTime& pose_at);

/// A frame's points placed at its stamp (frame.time) by place_at_stamp, when it times them; its
/// times are then dropped (nothing is left to deskew). Returns the points left as seen.
std::size_t place_frame_at_stamp(WorkloadFrame& frame, const PoseAtTime& pose_at);

}  // namespace eco::workloads
