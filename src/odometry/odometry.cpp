// The odometry's frame (odometry.hpp): preprocess, downsample, predict, register, update the map.

#include <eco/odometry/odometry.hpp>

#include "odometry/adaptive_threshold.hpp"
#include "odometry/point_to_plane.hpp"
#include "odometry/stopwatch.hpp"
#include "odometry/voxel_downsample.hpp"

#include <sys/resource.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace eco::odometry {
namespace {

/// Minor page faults of this process so far.
std::size_t minor_faults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return std::size_t(usage.ru_minflt);
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("odometry " + what);
}

/// The scan's finite points within [min_range, max_range] of the sensor, counting the others.
std::vector<Eigen::Vector3f> in_range(ScanView scan, const OdometryConfig& config, FrameReport& report) {
  std::vector<Eigen::Vector3f> kept;
  kept.reserve(scan.count);
  for (std::size_t i = 0; i < scan.count; ++i) {
    const Eigen::Vector3f p = scan[i];
    if (!p.allFinite()) {
      ++report.dropped_invalid;
      continue;
    }
    const double range = p.cast<double>().norm();
    if (range < config.min_range || range > config.max_range) {
      ++report.dropped_range;
      continue;
    }
    kept.push_back(p);
  }
  return kept;
}

/// Registration from `predicted`; when the scan then fits the map poorly (its share of points on
/// their planes under half the last frame's `usual_fit`: a turn begun or ended between frames,
/// which constant velocity cannot foresee and ICP does not recover from past a few degrees),
/// again from the prediction turned about the sensor's vertical axis, keeping the best fit.
/// `report` counts every iteration.
Alignment align_turning(PointToPlane& aligner, const LocalMap& map, std::span<const Eigen::Vector3d> source,
                        const Eigen::Isometry3d& predicted, const AlignSettings& settings, double usual_fit,
                        FrameReport& report) {
  const auto fits = [&](const Alignment& a) { return 2.0 * double(a.inliers) >= usual_fit * double(source.size()); };
  const auto count = [&](const Alignment& a) {
    report.iterations += a.iterations;
    report.query_ms += a.query_ms;
    report.solve_ms += a.solve_ms;
  };
  Alignment best = aligner.align(map, source, predicted, settings);
  count(best);
  for (double degrees : {6.0, -6.0, 12.0, -12.0, 18.0, -18.0}) {
    if (fits(best)) break;
    Eigen::Isometry3d turned = predicted;
    turned.rotate(Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, Eigen::Vector3d::UnitZ()));
    Alignment a = aligner.align(map, source, turned, settings);
    count(a);
    if (a.inliers > best.inliers) std::swap(a, best);
  }
  return best;
}

}  // namespace

void OdometryConfig::validate() const {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  require(positive(max_range), "max_range must be finite and > 0 m, got " + std::to_string(max_range));
  require(std::isfinite(min_range) && min_range >= 0.0 && min_range < max_range,
          "min_range must be >= 0 m and below max_range, got " + std::to_string(min_range));
  require(positive(voxel_size), "voxel_size must be finite and > 0 m, got " + std::to_string(voxel_size));
  require(neighbours >= 3, "neighbours must be >= 3 (a plane), got " + std::to_string(neighbours));
  require(positive(plane_tolerance), "plane_tolerance must be finite and > 0 m, got " + std::to_string(plane_tolerance));
  require(positive(plane_reach), "plane_reach must be finite and > 0 voxels, got " + std::to_string(plane_reach));
  require(positive(initial_threshold), "initial_threshold must be finite and > 0 m, got " + std::to_string(initial_threshold));
  require(std::isfinite(min_motion) && min_motion >= 0.0, "min_motion must be >= 0 m, got " + std::to_string(min_motion));
  require(max_iterations >= 1, "max_iterations must be >= 1, got " + std::to_string(max_iterations));
  require(positive(convergence), "convergence must be finite and > 0, got " + std::to_string(convergence));
  map_settings().validate();
}

MapSettings OdometryConfig::map_settings() const { return {box_side, voxel_size, max_points_per_voxel, threads}; }

struct Odometry::Impl {
  Impl(const OdometryConfig& c, std::unique_ptr<LocalMap> m)
      : config(c), map(std::move(m)), threshold(c.initial_threshold, c.min_motion, c.max_range) {}

  /// Constant velocity: the last motion again.
  [[nodiscard]] Eigen::Isometry3d prediction() const {
    if (poses.empty()) return start;
    if (poses.size() == 1) return poses.back();
    const Eigen::Isometry3d& last = poses.back();
    return orthonormal(last * (poses[poses.size() - 2].inverse() * last));
  }

  OdometryConfig config;
  std::unique_ptr<LocalMap> map;
  AdaptiveThreshold threshold;
  PointToPlane aligner;
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Isometry3d> poses;
  double last_fit = 0.0;  // the last registered frame's share of points on their planes (none: 0)
};

Odometry::Odometry(const OdometryConfig& config, std::unique_ptr<LocalMap> map) {
  config.validate();
  require(map != nullptr, "needs a map, got none");
  impl_ = std::make_unique<Impl>(config, std::move(map));
}

Odometry::~Odometry() = default;
Odometry::Odometry(Odometry&&) noexcept = default;
Odometry& Odometry::operator=(Odometry&&) noexcept = default;

void Odometry::set_start(const Eigen::Isometry3d& world_T_sensor) {
  require(impl_->poses.empty(), "start can only be set before the first frame");
  require(world_T_sensor.matrix().allFinite(), "start pose must be finite");
  impl_->start = world_T_sensor;
}

FrameReport Odometry::register_frame(ScanView scan) {
  Impl& o = *impl_;
  const OdometryConfig& c = o.config;
  const Stopwatch total;
  FrameReport report;
  report.index = o.poses.size();
  report.scan_points = scan.count;

  std::size_t faults = minor_faults();
  Stopwatch step;
  const std::vector<Eigen::Vector3f> kept = in_range(scan, c, report);
  report.preprocess_ms = step.ms();

  step = {};
  const std::vector<Eigen::Vector3f> frame = voxel_downsample(kept, 0.5 * c.voxel_size);
  const std::vector<Eigen::Vector3f> coarse = voxel_downsample(frame, 1.5 * c.voxel_size);
  std::vector<Eigen::Vector3d> source(coarse.size());
  for (std::size_t i = 0; i < coarse.size(); ++i) source[i] = coarse[i].cast<double>();
  report.downsample_ms = step.ms();
  report.map_input = frame.size();
  report.source = coarse.size();
  report.own_faults = minor_faults() - faults;
  faults = minor_faults();

  const Eigen::Isometry3d predicted = o.prediction();
  report.pose = predicted;
  report.threshold = o.threshold.max_distance();
  if (!o.poses.empty() && o.map->size() > 0 && !source.empty()) {
    AlignSettings settings;
    settings.neighbours = c.neighbours;
    settings.max_distance = report.threshold;
    settings.kernel_scale = o.threshold.sigma() / 3.0;
    settings.plane_tolerance = c.plane_tolerance;
    settings.plane_reach = c.plane_reach * c.voxel_size;
    settings.max_iterations = c.max_iterations;
    settings.convergence = c.convergence;
    settings.fit_distance = 0.1 * c.voxel_size;
    const Alignment aligned = align_turning(o.aligner, *o.map, source, predicted, settings, o.last_fit, report);
    o.last_fit = double(aligned.inliers) / double(source.size());
    report.pose = aligned.pose;
    report.registered = true;
    report.correspondences = aligned.correspondences;
    report.inliers = aligned.inliers;
    o.threshold.add(predicted.inverse() * aligned.pose);
  }

  step = {};
  o.map->update(report.pose, ScanView(frame));
  report.update_ms = step.ms();
  report.map_faults = minor_faults() - faults;
  report.map_points = o.map->size();
  o.poses.push_back(report.pose);
  report.total_ms = total.ms();
  return report;
}

const std::vector<Eigen::Isometry3d>& Odometry::poses() const { return impl_->poses; }
const LocalMap& Odometry::map() const { return *impl_->map; }
const OdometryConfig& Odometry::config() const { return impl_->config; }

}  // namespace eco::odometry
