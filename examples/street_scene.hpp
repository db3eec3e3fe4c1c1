#pragma once
// A tiny generated street for the demo: a vehicle driving ~1 m per frame between two facades,
// seen by a 64-beam spinning LiDAR (rays cast against the ground and the facades). Enough to
// show ECO at work with no download; the full simulator is a separate target.

#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <vector>

namespace eco::demo {

class StreetScene {
 public:
  static constexpr double kSensorHeight = 1.73;  // m above the ground
  static constexpr double kStreetHalfWidth = 12.0;
  static constexpr double kMaxRange = 80.0;

  explicit StreetScene(unsigned seed = 1) : rng_(seed) {}

  [[nodiscard]] Eigen::Isometry3d pose(int frame) const {
    const double x = 1.0 * frame;
    const double y = 4.0 * std::sin(x / 30.0);
    const double heading = std::atan2(4.0 / 30.0 * std::cos(x / 30.0), 1.0);
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    p.linear() = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    p.translation() = Eigen::Vector3d(x, y, 0.0);
    return p;
  }

  /// One revolution: 64 beams from +2 to -24.9 degrees, `columns` azimuth steps, in the sensor
  /// frame, with 2 cm range noise. Rays that hit nothing within range return nothing.
  std::vector<Eigen::Vector3f> scan(int frame, int columns = 900) {
    const Eigen::Isometry3d p = pose(frame);
    std::normal_distribution<double> noise(0.0, 0.02);
    std::vector<Eigen::Vector3f> out;
    for (int beam = 0; beam < 64; ++beam) {
      const double elevation = (2.0 - 26.9 * beam / 63.0) * M_PI / 180.0;
      for (int c = 0; c < columns; ++c) {
        const double azimuth = 2.0 * M_PI * c / columns;
        const Eigen::Vector3d dir(std::cos(elevation) * std::cos(azimuth),
                                  std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
        const double range = hit(p.translation(), p.linear() * dir);
        if (range > kMaxRange) continue;
        out.push_back(((range + noise(rng_)) * dir).cast<float>());
      }
    }
    return out;
  }

 private:
  /// Distance along a world ray to the ground or a facade (infinity if none).
  static double hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir) {
    double best = INFINITY;
    if (dir.z() < 0) best = std::min(best, (-kSensorHeight - origin.z()) / dir.z());
    for (double wall : {-kStreetHalfWidth, kStreetHalfWidth}) {
      const double t = (wall - origin.y()) / dir.y();
      if (t > 0) best = std::min(best, t);
    }
    return best;
  }

  std::mt19937 rng_;
};

}  // namespace eco::demo
