#pragma once
/// @file query_threads.hpp
/// Threads kept for batches of queries (MapReader::knn over a span): started once and woken for
/// each batch, as a registration loop asking some ten batches a frame wants (2,000 queries, k = 5,
/// on 2 cores: 0.47–0.50× one thread's time, against 0.55–0.60× with threads started per call).
///
///   eco::QueryThreads threads(2);                    // the calling thread and one helper
///   map.knn(queries, 5, out, found, threads);        // every iteration, no thread started
///
/// A process forked from the one that made them (Python's multiprocessing, a server's workers)
/// has none of the helpers, only their memory, whose locks may have been held at the fork: its
/// first batch starts helpers of its own and leaves the parent's untouched.

#include <atomic>
#include <functional>
#include <memory>

namespace eco {

class QueryThreads {
 public:
  /// `threads` >= 1, the calling thread counted: threads - 1 helpers are started. Throws
  /// std::invalid_argument for 0.
  explicit QueryThreads(unsigned threads);
  /// Stops and joins the helpers (this process's: a forked copy leaves the parent's alone).
  ~QueryThreads();
  QueryThreads(const QueryThreads&) = delete;
  QueryThreads& operator=(const QueryThreads&) = delete;

  /// The calling thread and the helpers.
  [[nodiscard]] unsigned size() const { return threads_; }

  /// Calls work() on the calling thread and on every helper at once, and returns when each has
  /// returned; rethrows the first exception one threw. Batches from several threads run one
  /// after the other.
  void run(const std::function<void()>& work);

 private:
  struct Crew;  // the helpers and what they share, in the process that started them
  Crew& crew();

  unsigned threads_;
  std::atomic<Crew*> crew_;
};

}  // namespace eco
