#include "bench/snapshot_timing.hpp"

#include "bench/query_batch.hpp"
#include "bench/stopwatch.hpp"
#include "bench/workload_source.hpp"

#include <eco/ego_octree.hpp>
#include <eco/workloads/workload.hpp>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

namespace eco::bench {
namespace {

/// A thread that queries the snapshot it is handed, without pause while told to read.
class Reader {
 public:
  Reader() : thread_([this] { run(); }) {}
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;
  ~Reader() {
    {
      const std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  /// Starts reading `snapshot` at `queries` (kept alive by the caller until pause()).
  void read(std::shared_ptr<const Snapshot> snapshot, const std::vector<Eigen::Vector3d>* queries) {
    {
      const std::lock_guard lock(mutex_);
      snapshot_ = std::move(snapshot);
      queries_ = queries;
      reading_ = true;
    }
    wake_.notify_all();
  }
  /// Stops reading and returns once the reader has let go of its snapshot.
  void pause() {
    reading_ = false;
    std::unique_lock lock(mutex_);
    idle_.wait(lock, [&] { return snapshot_ == nullptr; });
  }
  [[nodiscard]] std::size_t answered() const { return answered_.load(); }

 private:
  void run() {
    std::vector<Neighbor> found(5);
    std::unique_lock lock(mutex_);
    while (true) {
      wake_.wait(lock, [&] { return stop_ || snapshot_ != nullptr; });
      if (stop_) return;
      {
        const std::shared_ptr<const Snapshot> snapshot = snapshot_;
        const std::vector<Eigen::Vector3d>& queries = *queries_;
        lock.unlock();
        for (std::size_t i = 0; reading_.load(); i = (i + 1) % queries.size()) {
          (void)snapshot->knn(queries[i], std::span<Neighbor>(found));
          ++answered_;
        }
      }
      lock.lock();
      snapshot_ = nullptr;
      idle_.notify_all();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_, idle_;
  bool stop_ = false;
  std::atomic<bool> reading_{false};
  std::shared_ptr<const Snapshot> snapshot_;
  const std::vector<Eigen::Vector3d>* queries_ = nullptr;
  std::atomic<std::size_t> answered_{0};
  std::thread thread_;
};

}  // namespace

SnapshotTiming time_snapshots(const BenchOptions& options, const std::function<void(const std::string&)>& status) {
  OpenedWorkload workload = open_workload(options, status);
  const std::size_t total =
      options.frames > 0 ? std::min(options.frames, workload.frames->size()) : workload.frames->size();
  EgoOctree alone(options.config), publishing(options.config), beside(options.config);
  std::shared_ptr<const Snapshot> last;
  Reader reader;
  SnapshotTiming timing;
  std::vector<Neighbor> found(options.knn_k);
  double sink = 0.0;
  const auto batch = [&](const MapReader& map, const std::vector<Eigen::Vector3d>& queries) {
    const auto start = Clock::now();
    for (const Eigen::Vector3d& q : queries) {
      const std::size_t n = map.knn(q, std::span<Neighbor>(found));
      if (n > 0) sink += found[n - 1].sq_dist;
    }
    return ms_since(start);
  };
  for (std::size_t t = 0; t < total; ++t) {
    status("timing snapshots: frame " + std::to_string(t + 1) + " of " + std::to_string(total));
    const workloads::WorkloadFrame frame = workload.frames->frame(t);
    const std::vector<Eigen::Vector3d> queries =
        make_queries(frame, options.config.box_side, std::max<std::size_t>(options.knn_queries, 1), options.seed);
    std::optional<workloads::AttributedScan> attributed;
    const ScanView scan = workloads::scan_for(frame, options.config.attributes, attributed);
    const bool counted = t > 0;
    auto start = Clock::now();
    alone.update(frame.world_T_sensor, scan);
    const double update_alone = ms_since(start);
    if (last) reader.read(last, &queries);
    start = Clock::now();
    publishing.update(frame.world_T_sensor, scan);
    const double update_read = ms_since(start);
    start = Clock::now();
    beside.update(frame.world_T_sensor, scan);
    const double update_beside = ms_since(start);
    reader.pause();
    const Stats held = publishing.stats();
    start = Clock::now();
    last = publishing.snapshot();  // the one a frame older goes here
    const double publish = ms_since(start);
    // the same map twice, the tree and its snapshot, each first on every other frame
    double knn_live = 0.0, knn_snapshot = 0.0;
    if (t % 2 == 0) knn_live = batch(publishing, queries);
    knn_snapshot = batch(*last, queries);
    if (t % 2 == 1) knn_live = batch(publishing, queries);
    if (!counted) continue;
    timing.update_alone_ms += update_alone;
    timing.update_read_ms += update_read;
    timing.update_beside_ms += update_beside;
    timing.publish_ms += publish;
    timing.knn_live_ms += knn_live;
    timing.knn_snapshot_ms += knn_snapshot;
    timing.bytes_alone += double(alone.stats().bytes);
    timing.bytes_with_snapshot += double(held.bytes + held.snapshot_bytes);
    ++timing.frames;
  }
  if (timing.frames > 0) {
    const double n = double(timing.frames);
    for (double* mean : {&timing.update_alone_ms, &timing.update_read_ms, &timing.update_beside_ms, &timing.publish_ms, &timing.knn_live_ms,
                         &timing.knn_snapshot_ms, &timing.bytes_alone, &timing.bytes_with_snapshot}) {
      *mean /= n;
    }
  }
  timing.reader_queries = reader.answered() + (sink < 0 ? 1 : 0);
  return timing;
}

}  // namespace eco::bench
