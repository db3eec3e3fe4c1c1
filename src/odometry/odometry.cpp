// The odometry's frame (odometry.hpp): preprocess, downsample, predict, register, update the map.

#include <eco/odometry/odometry.hpp>

#include "odometry/adaptive_threshold.hpp"
#include "odometry/deskew.hpp"
#include "odometry/point_to_plane.hpp"
#include "odometry/stopwatch.hpp"
#include "odometry/voxel_downsample.hpp"

#include <sys/resource.h>

#include <algorithm>
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

/// The scan's finite points within [min_range, max_range] of the sensor, counting the others;
/// with `times` (one per point), the kept points' times into `kept_times`.
std::vector<Eigen::Vector3f> in_range(ScanView scan, std::span<const double> times, const OdometryConfig& config,
                                      FrameReport& report, std::vector<double>& kept_times) {
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
    if (!times.empty()) kept_times.push_back(times[i]);
  }
  return kept;
}

constexpr int kDeskewPasses = 4;     // registrations of a timed scan at most, each deskewed anew
constexpr double kSettled = 1e-3;    // [m, rad] a motion that changed less than this between passes

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

MapSettings OdometryConfig::map_settings() const {
  return {box_side, voxel_size, max_points_per_voxel, threads, std::min(max_range, box_side / 2)};
}

struct Odometry::Impl {
  Impl(const OdometryConfig& c, std::unique_ptr<LocalMap> m)
      : config(c), map(std::move(m)), threshold(c.initial_threshold, c.min_motion, c.max_range) {}

  /// Constant velocity: the last motion again.
  [[nodiscard]] Eigen::Isometry3d prediction() const {
    if (registered.empty()) return start;
    return orthonormal(registered.back() * last_motion());
  }
  /// The motion between the last two frames registered (the identity before there are two).
  [[nodiscard]] Eigen::Isometry3d last_motion() const {
    if (registered.size() < 2) return Eigen::Isometry3d::Identity();
    return registered[registered.size() - 2].inverse() * registered.back();
  }

  OdometryConfig config;
  std::unique_ptr<LocalMap> map;
  AdaptiveThreshold threshold;
  PointToPlane aligner;
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
  // where each scan was registered: at its stamp, or, for a scan whose points carry times, in the
  // middle of its sweep (deskew()); `poses` are all at the stamps
  std::vector<Eigen::Isometry3d> registered;
  std::vector<Eigen::Isometry3d> poses;
  // a timed first scan is placed at `start` as if in the middle of its sweep, half a motion off:
  // once the second gives the motion, the stamps' poses are moved by what it was off
  Eigen::Isometry3d first_offset = Eigen::Isometry3d::Identity();
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
  require(impl_->registered.empty(), "start can only be set before the first frame");
  require(world_T_sensor.matrix().allFinite(), "start pose must be finite");
  impl_->start = world_T_sensor;
}

FrameReport Odometry::register_frame(ScanView scan, std::span<const double> point_times) {
  Impl& o = *impl_;
  const OdometryConfig& c = o.config;
  require(point_times.empty() || point_times.size() == scan.count,
          "register_frame: " + std::to_string(point_times.size()) + " point times for " + std::to_string(scan.count) + " points");
  const Stopwatch total;
  FrameReport report;
  report.index = o.poses.size();
  report.scan_points = scan.count;

  std::size_t faults = minor_faults();
  Stopwatch step;
  std::vector<double> kept_times;
  const std::vector<Eigen::Vector3f> kept =
      in_range(scan, c.deskew ? point_times : std::span<const double>(), c, report, kept_times);
  const bool timed = !kept_times.empty();  // registered about the middle of its sweep
  report.preprocess_ms = step.ms();

  const Eigen::Isometry3d predicted = o.prediction();
  report.pose = predicted;
  report.threshold = o.threshold.max_distance();
  const bool registering = !o.registered.empty() && o.map->size() > 0;
  AlignSettings settings;
  settings.neighbours = c.neighbours;
  settings.max_distance = report.threshold;
  settings.kernel_scale = o.threshold.sigma() / 3.0;
  settings.plane_tolerance = c.plane_tolerance;
  settings.plane_reach = c.plane_reach * c.voxel_size;
  settings.max_iterations = c.max_iterations;
  settings.convergence = c.convergence;
  settings.fit_distance = 0.1 * c.voxel_size;

  // A timed scan is deskewed by the last frame's motion, registered, then deskewed again by the
  // motion its registration makes, until that motion settles: a turn begun during the frame
  // smears the scan by a rotation the last frame's motion does not have.
  Eigen::Isometry3d motion = o.last_motion();
  std::vector<Eigen::Vector3f> frame;
  for (int pass = 0; pass < (timed ? kDeskewPasses : 1); ++pass) {
    step = {};
    std::vector<Eigen::Vector3f> points = kept;
    if (timed && o.registered.size() + pass >= 2) {  // a motion to spread over the sweep
      deskew(points, kept_times, motion);
      report.deskewed = true;
    }
    report.preprocess_ms += step.ms();
    step = {};
    frame = voxel_downsample(points, 0.5 * c.voxel_size);
    const std::vector<Eigen::Vector3f> coarse = voxel_downsample(frame, 1.5 * c.voxel_size);
    std::vector<Eigen::Vector3d> source(coarse.size());
    for (std::size_t i = 0; i < coarse.size(); ++i) source[i] = coarse[i].cast<double>();
    report.downsample_ms += step.ms();
    report.map_input = frame.size();
    report.source = coarse.size();
    if (pass == 0) {
      report.own_faults = minor_faults() - faults;
      faults = minor_faults();
    }
    if (!registering || source.empty()) break;
    const Alignment aligned = pass == 0 ? align_turning(o.aligner, *o.map, source, predicted, settings, o.last_fit, report)
                                        : o.aligner.align(*o.map, source, report.pose, settings);
    if (pass > 0) {
      report.iterations += aligned.iterations;
      report.query_ms += aligned.query_ms;
      report.solve_ms += aligned.solve_ms;
    }
    o.last_fit = double(aligned.inliers) / double(source.size());
    report.pose = aligned.pose;
    report.registered = true;
    report.correspondences = aligned.correspondences;
    report.inliers = aligned.inliers;
    const Eigen::Isometry3d made = o.registered.back().inverse() * aligned.pose;
    const bool settled = pass > 0 && (made.translation() - motion.translation()).norm() < kSettled &&
                         Eigen::AngleAxisd(made.linear() * motion.linear().transpose()).angle() < kSettled;
    motion = made;
    if (!timed || settled) break;
  }
  if (report.registered) o.threshold.add(predicted.inverse() * report.pose);

  step = {};
  o.map->update(report.pose, ScanView(frame));
  report.update_ms = step.ms();
  report.map_faults = minor_faults() - faults;
  report.map_points = o.map->size();
  o.registered.push_back(report.pose);
  if (timed && o.registered.size() == 2) {
    const Eigen::Isometry3d first_middle = o.start * part_of(o.last_motion(), 0.5);
    o.first_offset = first_middle * o.start.inverse();
  }
  // back from the sweep's middle to the stamp, by half the motion just made
  if (timed && o.registered.size() >= 2) {
    report.pose = orthonormal(o.first_offset * report.pose * part_of(o.last_motion(), 0.5).inverse());
  }
  o.poses.push_back(report.pose);
  report.total_ms = total.ms();
  return report;
}

const std::vector<Eigen::Isometry3d>& Odometry::poses() const { return impl_->poses; }
const LocalMap& Odometry::map() const { return *impl_->map; }
const OdometryConfig& Odometry::config() const { return impl_->config; }

}  // namespace eco::odometry
