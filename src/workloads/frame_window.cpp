#include <eco/workloads/frame_window.hpp>

#include <stdexcept>
#include <string>

namespace eco::workloads {
namespace {

class FrameWindow final : public Workload {
 public:
  FrameWindow(std::unique_ptr<Workload> frames, std::size_t first) : frames_(std::move(frames)), first_(first) {}

  [[nodiscard]] std::size_t size() const override { return frames_->size() - first_; }
  [[nodiscard]] WorkloadFrame frame(std::size_t index) const override {
    WorkloadFrame f = frames_->frame(checked(index) + first_);
    f.index = index;
    return f;
  }
  [[nodiscard]] Eigen::Isometry3d pose(std::size_t index) const override { return frames_->pose(checked(index) + first_); }
  [[nodiscard]] std::string name() const override { return frames_->name(); }

 private:
  [[nodiscard]] std::size_t checked(std::size_t index) const {
    if (index >= size()) throw std::out_of_range("frame " + std::to_string(index) + " of " + std::to_string(size()));
    return index;
  }
  std::unique_ptr<Workload> frames_;
  std::size_t first_;
};

}  // namespace

std::unique_ptr<Workload> frame_window(std::unique_ptr<Workload> frames, std::size_t first) {
  if (first == 0) return frames;
  if (first >= frames->size()) {
    throw std::invalid_argument("--start " + std::to_string(first) + " is past the last of the " +
                                std::to_string(frames->size()) + " frames");
  }
  return std::make_unique<FrameWindow>(std::move(frames), first);
}

}  // namespace eco::workloads
