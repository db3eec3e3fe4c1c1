#pragma once
// The simulator's drive as a workload, frames made in memory on demand: the benchmark's
// default when no data folder is given.

#include <eco/sim/simulator.hpp>
#include <eco/workloads/workload.hpp>

namespace eco::bench {

class SimWorkload final : public workloads::Workload {
 public:
  explicit SimWorkload(const sim::SimConfig& config) : sim_(config) {}

  [[nodiscard]] std::size_t size() const override { return sim_.size(); }
  [[nodiscard]] workloads::WorkloadFrame frame(std::size_t index) const override {
    sim::SimFrame f = sim_.frame(index);
    return {index, f.world_T_lidar, std::move(f.cloud.points), std::move(f.labels), std::move(f.cloud.intensity),
            f.time, std::move(f.point_times)};
  }
  [[nodiscard]] Eigen::Isometry3d pose(std::size_t index) const override { return sim_.pose(index); }
  [[nodiscard]] std::string name() const override { return "dynamic"; }

 private:
  sim::Simulator sim_;
};

}  // namespace eco::bench
