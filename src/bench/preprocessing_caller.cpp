#include "bench/preprocessing_caller.hpp"

#include "bench/stopwatch.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <bit>
#include <functional>
#include <vector>

namespace eco::bench {
namespace {

using Points = std::vector<Eigen::Vector3d>;

/// One point a voxel of side `voxel`, the first to come (KISS-ICP's VoxelDownsample), through an
/// open-addressing table reserved for every point as a robin-map is: twice as many slots, rounded
/// up to a power of two, in one block.
Points downsample(const Points& points, double voxel) {
  struct Slot {
    VoxelKey key;
    Eigen::Vector3d point;
    bool used = false;
  };
  const std::size_t slots = std::bit_ceil(std::max<std::size_t>(2 * points.size(), 2));
  std::vector<Slot> table(slots);
  std::size_t used = 0;
  for (const Eigen::Vector3d& p : points) {
    const VoxelKey key = voxel_of(p, voxel);
    for (std::size_t at = std::hash<VoxelKey>()(key) & (slots - 1);; at = (at + 1) & (slots - 1)) {
      if (!table[at].used) {
        table[at] = {key, p, true};
        ++used;
        break;
      }
      if (table[at].key == key) break;
    }
  }
  Points kept;
  kept.reserve(used);
  for (const Slot& slot : table)
    if (slot.used) kept.push_back(slot.point);
  return kept;
}

double sum_of(const Points& points) {
  double sum = 0.0;
  for (const Eigen::Vector3d& p : points) sum += p.sum();
  return sum;
}

}  // namespace

PreprocessingCaller::PreprocessingCaller() : thread_([this] { serve(); }) {}

PreprocessingCaller::~PreprocessingCaller() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void PreprocessingCaller::serve() {
  std::unique_lock lock(mutex_);
  while (true) {
    changed_.wait(lock, [&] { return stopping_ || job_ != nullptr; });
    if (stopping_) return;
    (*job_)();
    job_ = nullptr;
    changed_.notify_all();
  }
}

void PreprocessingCaller::on_second_thread(const std::function<void()>& job) {
  std::unique_lock lock(mutex_);
  job_ = &job;
  changed_.notify_all();
  changed_.wait(lock, [&] { return job_ == nullptr; });
}

CallerWork PreprocessingCaller::run(const ScanView& scan) {
  CallerWork work;
  const long faults = minor_faults();
  const auto start = Clock::now();
  {
    Points frame(scan.count);
    for (std::size_t i = 0; i < scan.count; ++i) {
      const float* p = scan.data + i * scan.stride;
      frame[i] = Eigen::Vector3d(p[0], p[1], p[2]);
    }
    Points inliers;  // KISS-ICP's range filter, 0 < |p| < 100 m, into a vector grown as points come
    for (const Eigen::Vector3d& p : frame)
      if (const double r = p.norm(); r > 0.0 && r < 100.0) inliers.push_back(p);
    Points corrected;  // the motion correction, on the second thread
    Points source;
    on_second_thread([&] {
      const Eigen::Isometry3d motion(Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitZ()));
      corrected.resize(inliers.size());
      for (std::size_t i = 0; i < inliers.size(); ++i) corrected[i] = motion * inliers[i];
      source = downsample(corrected, 1.5);
    });
    const Points frame_downsampled = downsample(corrected, 0.5);
    work.sum = sum_of(source) + sum_of(frame_downsampled);
  }
  work.ms = ms_since(start);
  work.faults = minor_faults() - faults;
  return work;
}

}  // namespace eco::bench
