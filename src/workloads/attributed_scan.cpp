#include <eco/workloads/workload.hpp>

#include <numeric>

namespace eco::workloads {

AttributedScan::AttributedScan(const WorkloadFrame& frame, std::uint32_t first_id)
    : ids(frame.points.size()),
      intensities(frame.intensities.empty() ? std::vector<float>(frame.points.size()) : frame.intensities),
      times(frame.points.size(), frame.time),
      view(frame.points) {
  std::iota(ids.begin(), ids.end(), first_id);
  view.ids = ids.data();
  view.intensities = intensities.data();
  view.times = times.data();
}

ScanView scan_for(const WorkloadFrame& frame, const KeptAttributes& kept, std::optional<AttributedScan>& attributed) {
  if (!kept.any()) return ScanView(frame.points);
  attributed.emplace(frame, std::uint32_t(frame.index << 20));
  return attributed->view;
}

}  // namespace eco::workloads
