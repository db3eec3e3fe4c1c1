#pragma once
/// @file static_workload.hpp
/// The paper's static workload: at each pose of a sequence, the points of the static map inside
/// the box of side L centred on the sensor, [p - L/2, p + L/2) per world axis, given in the
/// sensor frame.

#include <eco/workloads/static_map.hpp>
#include <eco/workloads/workload.hpp>

#include <memory>
#include <span>

namespace eco::workloads {

class StaticWorkload final : public Workload {
 public:
  /// Throws std::invalid_argument if `box_side` is not positive and finite or `map` is null.
  StaticWorkload(std::shared_ptr<const StaticMap> map, std::span<const Eigen::Isometry3d> poses,
                 double box_side = 20.0);

  [[nodiscard]] std::size_t size() const override { return poses_.size(); }
  [[nodiscard]] WorkloadFrame frame(std::size_t index) const override;
  [[nodiscard]] Eigen::Isometry3d pose(std::size_t index) const override { return poses_.at(index); }
  [[nodiscard]] std::string name() const override { return "static"; }
  [[nodiscard]] const StaticMap& map() const { return *map_; }

 private:
  std::shared_ptr<const StaticMap> map_;
  std::vector<Eigen::Isometry3d> poses_;
  double box_side_;
};

}  // namespace eco::workloads
