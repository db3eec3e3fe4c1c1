#include <eco/workloads/static_workload.hpp>

#include <cmath>
#include <stdexcept>
#include <string>

namespace eco::workloads {

StaticWorkload::StaticWorkload(std::shared_ptr<const StaticMap> map,
                               std::span<const Eigen::Isometry3d> poses, double box_side)
    : map_(std::move(map)), poses_(poses.begin(), poses.end()), box_side_(box_side) {
  if (!map_) throw std::invalid_argument("eco::workloads::StaticWorkload: no map");
  if (!(box_side > 0.0) || !std::isfinite(box_side)) {
    throw std::invalid_argument("eco::workloads::StaticWorkload: box_side = " +
                                std::to_string(box_side) + " must be positive and finite");
  }
}

WorkloadFrame StaticWorkload::frame(std::size_t index) const {
  if (index >= poses_.size()) {
    throw std::out_of_range("eco::workloads::StaticWorkload: frame " + std::to_string(index) +
                            " of " + std::to_string(poses_.size()));
  }
  WorkloadFrame frame;
  frame.index = index;
  frame.world_T_sensor = poses_[index];
  frame.time = double(index) / 10.0;
  const Eigen::Vector3d centre = poses_[index].translation();
  const Eigen::Vector3d half = Eigen::Vector3d::Constant(box_side_ / 2.0);
  const Eigen::Isometry3d sensor_T_world = poses_[index].inverse();
  map_->for_each_in_box(centre - half, centre + half, [&](const Eigen::Vector3d& p) {
    frame.points.push_back((sensor_T_world * p).cast<float>());
  });
  return frame;
}

}  // namespace eco::workloads
