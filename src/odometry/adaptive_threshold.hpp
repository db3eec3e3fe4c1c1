#pragma once
// How far a correspondence may reach: three standard deviations of how wrong the constant-velocity
// prediction has been (KISS-ICP's adaptive threshold, Vizzo et al. 2023). A prediction's error is
// measured as the farthest a point at max_range moves between the predicted and the estimated
// pose; errors below min_motion (standing still) are not sampled.

#include <Eigen/Geometry>

#include <cmath>
#include <cstddef>

namespace eco::odometry {

class AdaptiveThreshold {
 public:
  AdaptiveThreshold(double initial, double min_motion, double max_range)
      : initial_(initial), min_motion_(min_motion), max_range_(max_range) {}

  /// The motion model's error so far [m]: its RMS, or the initial guess before any sample.
  [[nodiscard]] double sigma() const { return samples_ == 0 ? initial_ : std::sqrt(sum_sq_ / double(samples_)); }
  /// The correspondence distance [m] the next registration uses.
  [[nodiscard]] double max_distance() const { return 3.0 * sigma(); }

  /// Samples the error of a prediction that `deviation` (predicted^-1 * estimated) corrected.
  void add(const Eigen::Isometry3d& deviation) {
    const double angle = Eigen::AngleAxisd(deviation.linear()).angle();
    const double error = 2.0 * max_range_ * std::sin(angle / 2.0) + deviation.translation().norm();
    if (error < min_motion_) return;
    sum_sq_ += error * error;
    ++samples_;
  }

 private:
  double initial_;
  double min_motion_;
  double max_range_;
  double sum_sq_ = 0.0;
  std::size_t samples_ = 0;
};

}  // namespace eco::odometry
