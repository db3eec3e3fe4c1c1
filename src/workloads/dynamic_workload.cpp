#include <eco/workloads/dynamic_workload.hpp>

namespace eco::workloads {

WorkloadFrame DynamicWorkload::frame(std::size_t index) const {
  io::KittiFrame scan = sequence_.read(index);
  std::vector<std::uint32_t> labels;
  if (sequence_.has_labels()) labels = sequence_.read_labels(index);
  const std::span<const double> times = sequence_.times();
  const double time = index < times.size() ? times[index] : double(index) / 10.0;
  return {index, scan.world_T_lidar, std::move(scan.cloud.points), std::move(labels),
          std::move(scan.cloud.intensity), time, {}};
}

}  // namespace eco::workloads
