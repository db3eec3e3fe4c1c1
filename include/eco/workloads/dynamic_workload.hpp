#pragma once
/// @file dynamic_workload.hpp
/// The paper's dynamic workload: the raw scans of a sequence, one per frame, read from disk
/// only when asked for.

#include <eco/io/kitti_sequence.hpp>
#include <eco/workloads/workload.hpp>

namespace eco::workloads {

class DynamicWorkload final : public Workload {
 public:
  explicit DynamicWorkload(io::KittiSequence sequence) : sequence_(std::move(sequence)) {}

  [[nodiscard]] std::size_t size() const override { return sequence_.size(); }
  [[nodiscard]] WorkloadFrame frame(std::size_t index) const override;
  [[nodiscard]] Eigen::Isometry3d pose(std::size_t index) const override {
    return sequence_.poses()[index];
  }
  [[nodiscard]] std::string name() const override { return "dynamic"; }
  [[nodiscard]] const io::KittiSequence& sequence() const { return sequence_; }

 private:
  io::KittiSequence sequence_;
};

}  // namespace eco::workloads
