#pragma once
// Milliseconds since a point in time: what the odometry reports of each step.

#include <chrono>

namespace eco::odometry {

class Stopwatch {
 public:
  [[nodiscard]] double ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace eco::odometry
