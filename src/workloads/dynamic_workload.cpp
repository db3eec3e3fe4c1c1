#include <eco/workloads/dynamic_workload.hpp>

namespace eco::workloads {

WorkloadFrame DynamicWorkload::frame(std::size_t index) const {
  io::KittiFrame scan = sequence_.read(index);
  return {index, scan.world_T_lidar, std::move(scan.cloud.points)};
}

}  // namespace eco::workloads
