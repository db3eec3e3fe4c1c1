#pragma once
// The odometry (eco/odometry/odometry.hpp) run with several maps over the same frames, and what
// `eco odometry` writes of it: per map poses.txt and frames.csv, then summary.md, summary.json and
// trajectory.svg for all.

#include <eco/odometry/odometry.hpp>
#include <eco/odometry/trajectory_errors.hpp>
#include <eco/workloads/workload.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace eco::bench {

/// One map's run.
struct OdometryRun {
  std::string map;
  bool exact = true;
  std::vector<odometry::FrameReport> frames;
  std::vector<Eigen::Isometry3d> poses;
  std::optional<odometry::TrajectoryErrors> errors;  // with reference poses
};

/// What the frames of a run cost, averaged (after the first frame, which has nothing to register).
struct OdometryFigures {
  double frame_ms = 0.0, p99_ms = 0.0;
  double own_ms = 0.0;     // preprocessing and downsampling
  double query_ms = 0.0, solve_ms = 0.0, update_ms = 0.0;
  double own_faults = 0.0, map_faults = 0.0;  // per frame
  double iterations = 0.0;
  std::size_t map_points = 0;  // after the last frame
};
[[nodiscard]] OdometryFigures figures_of(const OdometryRun& run);
/// The runs in a table that fits a terminal: time per frame, over ECO's, the map's share, the
/// accuracy (summary.md has every figure).
[[nodiscard]] std::string brief_odometry_table(const std::vector<OdometryRun>& runs);

/// Whether `map`'s queries are exact; throws std::invalid_argument for an unknown name. Made
/// without helper threads, so that the caller may still fork.
[[nodiscard]] bool map_is_exact(const std::string& map, const odometry::OdometryConfig& config);

/// Runs the odometry under `config` with each of `maps` on frames [0, frames) of `scans`, one map
/// after the other, each in a process of its own (forked: one map's heap does not shape the
/// next's page faults), so the caller must run no other thread (fork_alone.hpp). With `reference` (one pose per frame) each run starts at its first pose
/// and is scored against it. `observe` is shown each frame once registered (in the child).
using FrameObserver = std::function<void(const std::string& map, const odometry::Odometry&, const odometry::FrameReport&)>;
[[nodiscard]] std::vector<OdometryRun> run_odometry(const workloads::Workload& scans, std::size_t frames,
                                                    const std::vector<std::string>& maps,
                                                    const odometry::OdometryConfig& config,
                                                    std::span<const Eigen::Isometry3d> reference,
                                                    const FrameObserver& observe = {});

/// How the estimate is written: world_T_lidar, or KITTI's camera-0 poses when `velo_to_cam` is given.
struct PoseOutput {
  std::optional<Eigen::Isometry3d> velo_to_cam;
};

/// Writes <out>/<map>/poses.txt and frames.csv for each run, then summary.md, summary.json and
/// trajectory.svg; returns brief_odometry_table(runs). `source` names the frames in the summary.
std::string write_odometry_results(const std::filesystem::path& out, const std::string& source,
                                   const std::vector<OdometryRun>& runs, std::span<const Eigen::Isometry3d> reference,
                                   const PoseOutput& poses);

}  // namespace eco::bench
