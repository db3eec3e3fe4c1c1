#include <eco/query_threads.hpp>

#include <unistd.h>

#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace eco {
namespace {

/// Runs `work`; what it throws, if anything, comes back rather than leaving the thread.
std::exception_ptr run_catching(const std::function<void()>& work) {
  try {
    work();
  } catch (...) {
    return std::current_exception();
  }
  return nullptr;
}

}  // namespace

struct QueryThreads::Crew {
  explicit Crew(unsigned helper_count) {
    for (unsigned i = 0; i < helper_count; ++i) helpers.emplace_back([this] { serve(); });
  }
  ~Crew() {
    {
      const std::lock_guard lock(mutex);
      stopping = true;
    }
    wake.notify_all();
    for (std::thread& helper : helpers) helper.join();
  }
  Crew(const Crew&) = delete;
  Crew& operator=(const Crew&) = delete;

  void run(const std::function<void()>& work) {
    const std::lock_guard one_at_a_time(batch);
    {
      const std::lock_guard lock(mutex);
      work_ = &work;
      busy = unsigned(helpers.size());
      failure = nullptr;
      ++batches;
    }
    wake.notify_all();
    const std::exception_ptr mine = run_catching(work);
    std::unique_lock lock(mutex);
    done.wait(lock, [&] { return busy == 0; });
    work_ = nullptr;
    if (mine) std::rethrow_exception(mine);
    if (failure) std::rethrow_exception(failure);
  }

  void serve() {
    std::uint64_t served = 0;
    std::unique_lock lock(mutex);
    for (;;) {
      wake.wait(lock, [&] { return stopping || batches != served; });
      if (stopping) return;
      served = batches;
      const std::function<void()>& work = *work_;
      lock.unlock();
      const std::exception_ptr failed = run_catching(work);
      lock.lock();
      if (failed && !failure) failure = failed;
      if (--busy == 0) done.notify_one();
    }
  }

  const pid_t pid = getpid();
  std::vector<std::thread> helpers;
  std::mutex batch;  // one batch at a time
  std::mutex mutex;  // what follows
  std::condition_variable wake, done;
  const std::function<void()>* work_ = nullptr;
  std::uint64_t batches = 0;
  unsigned busy = 0;  // helpers still in the batch
  bool stopping = false;
  std::exception_ptr failure;
};

QueryThreads::QueryThreads(unsigned threads) : threads_(threads) {
  if (threads == 0) throw std::invalid_argument("eco::QueryThreads: threads = 0 must be >= 1");
  crew_ = new Crew(threads - 1);
}

QueryThreads::~QueryThreads() {
  Crew* crew = crew_.load();
  // a crew made before a fork is the parent's: its threads are not here to join, and its memory is
  // left as it is (freeing it would run destructors on locks a parent's thread may have held)
  if (crew->pid == getpid()) delete crew;
}

QueryThreads::Crew& QueryThreads::crew() {
  Crew* current = crew_.load(std::memory_order_acquire);
  if (current->pid == getpid()) return *current;
  auto own = std::make_unique<Crew>(threads_ - 1);
  // two threads of the forked process may get here at once: one crew is kept, the other joined
  if (crew_.compare_exchange_strong(current, own.get(), std::memory_order_acq_rel)) return *own.release();
  return *current;
}

void QueryThreads::run(const std::function<void()>& work) { crew().run(work); }

}  // namespace eco
