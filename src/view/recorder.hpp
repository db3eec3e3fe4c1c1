#pragma once
// What `eco run --record` and `eco odometry --record` write for the viewer: per frame a frame file
// (frame_file.hpp) and a line of view/frames.csv (the path, the reference path, the figures the map
// reported), and once view/run.json (what was run). The recorder finds what each frame inserted,
// dropped and cleared by comparing the held points with the last frame's, so it works for any map
// that can list its points.

#include "view/birth_table.hpp"
#include "view/frame_file.hpp"
#include "view/run_index.hpp"

#include <eco/config.hpp>
#include <eco/types.hpp>

#include <Eigen/Geometry>

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace eco::view {

/// What was run, for the page's title and scales.
struct RunInfo {
  std::string title;         ///< "simulated drive", a data folder, "odometry on eco"
  double box_side = 0.0;     ///< [m]; points that leave the cube count as dropped (0: every removal does)
  double voxel_size = 0.1;   ///< [m] of the voxel map recorded
  std::size_t frames = 0;    ///< frames the run will have, when known (0: unknown)
  bool has_reference = false;  ///< frames come with a reference position (an odometry's ground truth)
  /// False when the map does not count what it inserted, dropped and cleared (an odometry's
  /// maps): frames.csv then gets the recorder's own counts.
  bool map_counts = true;
  /// The region the map holds in the cube, drawn instead of it (its size each frame from
  /// FrameFigures::region).
  RegionShape region = RegionShape::Cube;
  TurnWith turn_with = TurnWith::Yaw;
};

/// What the recorder found changed since the last frame it recorded.
struct FrameChanges {
  std::size_t inserted = 0, dropped = 0, cleared = 0;
};

class Recorder {
 public:
  /// Records into `folder` (created), replacing any recording there.
  Recorder(const std::string& folder, const RunInfo& info);
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  /// Records frame `frame`: the map's `held` points (world frame) and `voxels` (keys at
  /// RunInfo::voxel_size) after its update at `world_T_sensor`, with the figures it reported.
  FrameChanges record(std::uint32_t frame, const Eigen::Isometry3d& world_T_sensor, const std::vector<HeldPoint>& held,
                      const std::vector<VoxelKey>& voxels, FrameFigures figures,
                      const std::optional<Eigen::Vector3d>& reference = std::nullopt);

  /// Takes `held` as what the map held after frame `frame`, without recording it: a run that goes
  /// on from a saved map then shows its first frame's changes, not every loaded point as new.
  void carry(std::uint32_t frame, const std::vector<HeldPoint>& held);

  [[nodiscard]] const std::string& folder() const { return folder_; }

 private:
  std::string folder_;
  RunInfo info_;
  BirthTable births_;  // carried over: a frame adds and forgets only what changed
  std::FILE* index_ = nullptr;  // frames.csv, a line a frame, flushed as written
};

/// The voxels at `voxel_size` that hold at least one of `held`, for a map that has no voxel map of its own.
[[nodiscard]] std::vector<VoxelKey> occupied_voxels(const std::vector<HeldPoint>& held, double voxel_size);

}  // namespace eco::view
