#pragma once
// A caller that allocates as KISS-ICP's preprocessing does (kiss_icp/pipeline, preprocessing.cpp,
// voxelization.cpp), for measuring what a map beside it costs in page faults: every frame the scan
// copied into a vector of doubles, a range-filtered copy, a motion-corrected copy made by a second
// thread (KISS-ICP's are TBB's), and two voxel downsamplings through hash maps (one on each
// thread), all freed by the frame's end. These are a few scan-sized blocks a frame: the C library
// serves them from its heap or maps them fresh, depending on thresholds the rest of the process
// moves.

#include "bench/caller_work.hpp"

#include <eco/types.hpp>

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace eco::bench {

class PreprocessingCaller {
 public:
  PreprocessingCaller();
  ~PreprocessingCaller();
  PreprocessingCaller(const PreprocessingCaller&) = delete;
  PreprocessingCaller& operator=(const PreprocessingCaller&) = delete;

  /// One frame's preprocessing of `scan`, timed, with the page faults of both threads.
  [[nodiscard]] CallerWork run(const ScanView& scan);

 private:
  /// Runs `job` on the second thread and waits for it.
  void on_second_thread(const std::function<void()>& job);
  void serve();

  std::mutex mutex_;
  std::condition_variable changed_;
  const std::function<void()>* job_ = nullptr;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace eco::bench
