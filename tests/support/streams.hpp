#pragma once
// Deterministic pose-and-scan streams for the oracle tests: motion patterns times point
// distributions, seeded.

#include <eco/config.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace eco::test {

enum class Motion { Smooth, Still, SubQuantum, Backwards, Diagonal, Teleport };
enum class Cloud { Uniform, Surfaces, Duplicates, Few };

inline std::string name(Motion m) {
  const char* names[] = {"Smooth", "Still", "SubQuantum", "Backwards", "Diagonal", "Teleport"};
  return names[int(m)];
}
inline std::string name(Cloud c) {
  const char* names[] = {"Uniform", "Surfaces", "Duplicates", "Few"};
  return names[int(c)];
}

inline std::string name(Recentring r) { return r == Recentring::Exact ? "Exact" : "Quantised"; }
inline std::string mode_name(const ::testing::TestParamInfo<Recentring>& param) { return name(param.param); }

/// A sensor moving by `motion` through scans shaped by `cloud`, for a box of side `box_side`.
class Stream {
 public:
  Stream(Motion motion, Cloud cloud, double box_side, unsigned seed)
      : motion_(motion), cloud_(cloud), side_(box_side), rng_(seed) {}

  /// The sensor pose of frame t (t = 0, 1, ...).
  [[nodiscard]] Eigen::Isometry3d pose(int t) const {
    const double s = side_ / 20.0;  // motion scales with the box
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    double yaw = 0.0;
    switch (motion_) {
      case Motion::Smooth:
        p = {0.9 * s * t, 3.0 * s * std::sin(t / 10.0), 0.2 * s * std::sin(t / 7.0)};
        yaw = 0.3 * std::sin(t / 15.0);
        break;
      case Motion::Still:
        p = {1.25, -0.5, 0.25};
        yaw = 0.7;
        break;
      case Motion::SubQuantum:
        p = {0.07 * s * t, -0.03 * s * t, 0.0};
        yaw = 0.01 * t;
        break;
      case Motion::Backwards:
        p = {-1.1 * s * t, 0.1 * s * t, 0.0};
        yaw = M_PI;
        break;
      case Motion::Diagonal:
        p = {0.8 * s * t, 0.8 * s * t, 0.4 * s * t};
        yaw = M_PI / 4;
        break;
      case Motion::Teleport:
        p = {0.9 * s * t + 2.5 * side_ * (t / 6), 2.5 * side_ * (t / 6), 0.0};
        yaw = 0.2 * t;
        break;
    }
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    pose.translation() = p;
    return pose;
  }

  /// A scan in the sensor frame; reaches past the box so some points fall outside it, and
  /// carries a few NaN and infinite points.
  std::vector<Eigen::Vector3f> scan(int t) {
    std::vector<Eigen::Vector3f> out;
    const double reach = 0.75 * side_;
    std::uniform_real_distribution<double> u(-reach, reach);
    std::normal_distribution<double> noise(0.0, 0.02 * side_ / 20.0);
    switch (cloud_) {
      case Cloud::Uniform:
        for (int i = 0; i < 250; ++i) out.push_back(vec(u(rng_), u(rng_), u(rng_)));
        break;
      case Cloud::Surfaces:
        for (int i = 0; i < 250; ++i) {
          const int kind = i % 5;
          if (kind < 2) {
            out.push_back(vec(u(rng_), u(rng_), -0.08 * side_ + noise(rng_)));  // ground
          } else if (kind < 4) {
            out.push_back(vec(u(rng_), (kind == 2 ? 0.3 : -0.3) * side_ + noise(rng_), u(rng_) / 3));
          } else {  // a pole: a dense cluster
            out.push_back(vec(0.2 * side_ + noise(rng_), 0.1 * side_ + noise(rng_), u(rng_) / 4));
          }
        }
        break;
      case Cloud::Duplicates: {
        std::vector<Eigen::Vector3f> distinct;
        for (int i = 0; i < 20; ++i) distinct.push_back(vec(u(rng_), u(rng_), u(rng_) / 4));
        for (int i = 0; i < 200; ++i) out.push_back(distinct[std::size_t(i) % distinct.size()]);
        break;
      }
      case Cloud::Few:
        for (int i = 0; i < t % 4; ++i) out.push_back(vec(u(rng_) / 2, u(rng_) / 2, u(rng_) / 2));
        break;
    }
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    if (t % 3 == 0) out.insert(out.begin(), Eigen::Vector3f(nan, 0.f, 1.f));
    if (t % 4 == 1) out.push_back(Eigen::Vector3f(1.f, -inf, 0.f));
    return out;
  }

  std::mt19937& rng() { return rng_; }

 private:
  static Eigen::Vector3f vec(double x, double y, double z) { return {float(x), float(y), float(z)}; }

  Motion motion_;
  Cloud cloud_;
  double side_;
  std::mt19937 rng_;
};

}  // namespace eco::test
