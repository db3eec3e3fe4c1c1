// eco::keep_freed_heap (include/eco/process_heap.hpp): a frame loop that allocates a few
// scan-sized buffers and frees them by the frame's end faults its pages afresh after its first
// frame as the process starts (glibc maps the first frame's buffers and, once they are freed,
// serves the next ones from a heap that has yet to grow), and not once the call is made. Each case runs in a child process of its own,
// since the C library's heap remembers what a run did. Skipped under AddressSanitizer, whose
// allocator has no such settings (make test runs it in the release build).

#include "bench/preprocessing_caller.hpp"
#include "support/sanitizers.hpp"

#include <eco/process_heap.hpp>

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstddef>
#include <random>
#include <vector>

namespace eco::test {
namespace {

/// Page faults a frame of a caller that allocates as KISS-ICP's preprocessing does (two threads,
/// a few scan-sized buffers a frame) over scans of 120,000 random points, the first frame (which
/// builds everything) left out.
long faults_a_frame(bool keep_freed_heap) {
  if (keep_freed_heap && !eco::keep_freed_heap()) return -1;
  constexpr int kFrames = 16;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> coordinate(-60.0f, 60.0f);
  bench::PreprocessingCaller caller;
  long faults = 0;
  for (int frame = 0; frame < kFrames; ++frame) {
    std::vector<Eigen::Vector3f> scan(120'000);
    for (Eigen::Vector3f& p : scan) p = {coordinate(rng), coordinate(rng), coordinate(rng)};
    const bench::CallerWork work = caller.run(ScanView(scan));
    if (frame > 0) faults += work.faults;
  }
  return faults / (kFrames - 1);
}

/// faults_a_frame in a child process.
long faults_a_frame_alone(bool keep_freed_heap) {
  int ends[2];
  if (pipe(ends) != 0) return -2;
  const pid_t child = fork();  // the test runs no other thread
  if (child == 0) {
    const long faults = faults_a_frame(keep_freed_heap);
    _exit(write(ends[1], &faults, sizeof faults) == ssize_t(sizeof faults) ? 0 : 1);
  }
  long faults = -3;
  if (read(ends[0], &faults, sizeof faults) != ssize_t(sizeof faults)) faults = -4;
  close(ends[0]);
  close(ends[1]);
  int status = 0;
  waitpid(child, &status, 0);
  return faults;
}

TEST(KeepFreedHeap, AFrameLoopStopsFaultingFreshPages) {
  if (kAddressSanitizer) GTEST_SKIP() << "AddressSanitizer's allocator has no thresholds to set";
  const long as_started = faults_a_frame_alone(false);
  const long kept = faults_a_frame_alone(true);
  ASSERT_GE(kept, 0) << "eco::keep_freed_heap() refused";
  EXPECT_GT(as_started, 200) << "this loop no longer faults as the process starts: the test shows nothing";
  EXPECT_LT(kept, 16) << "as the process starts: " << as_started;
}

}  // namespace
}  // namespace eco::test
