#pragma once
/// @file query_threads.hpp
/// Threads kept for batches of queries (MapReader::knn over a span): started once and woken for
/// each batch, as a registration loop asking some ten batches a frame wants (2,000 queries, k = 5,
/// on 2 cores: 0.47–0.50× one thread's time, against 0.55–0.60× with threads started per call).
///
///   eco::QueryThreads threads(2);                    // the calling thread and one helper
///   map.knn(queries, 5, out, found, threads);        // every iteration, no thread started

#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace eco {

class QueryThreads {
 public:
  /// `threads` >= 1, the calling thread counted: threads - 1 helpers are started. Throws
  /// std::invalid_argument for 0.
  explicit QueryThreads(unsigned threads);
  /// Stops and joins the helpers.
  ~QueryThreads();
  QueryThreads(const QueryThreads&) = delete;
  QueryThreads& operator=(const QueryThreads&) = delete;

  /// The calling thread and the helpers.
  [[nodiscard]] unsigned size() const { return unsigned(helpers_.size()) + 1; }

  /// Calls work() on the calling thread and on every helper at once, and returns when each has
  /// returned; rethrows the first exception one threw. Batches from several threads run one
  /// after the other.
  void run(const std::function<void()>& work);

 private:
  void serve();

  std::vector<std::thread> helpers_;
  std::mutex batch_;  // one batch at a time
  std::mutex mutex_;  // what follows
  std::condition_variable wake_, done_;
  const std::function<void()>* work_ = nullptr;
  std::uint64_t batches_ = 0;
  unsigned busy_ = 0;  // helpers still in the batch
  bool stopping_ = false;
  std::exception_ptr failure_;
};

}  // namespace eco
