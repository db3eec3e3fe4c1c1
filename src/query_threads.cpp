#include <eco/query_threads.hpp>

#include <stdexcept>

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

QueryThreads::QueryThreads(unsigned threads) {
  if (threads == 0) throw std::invalid_argument("eco::QueryThreads: threads = 0 must be >= 1");
  for (unsigned i = 1; i < threads; ++i) helpers_.emplace_back([this] { serve(); });
}

QueryThreads::~QueryThreads() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (std::thread& helper : helpers_) helper.join();
}

void QueryThreads::run(const std::function<void()>& work) {
  const std::lock_guard one_at_a_time(batch_);
  {
    const std::lock_guard lock(mutex_);
    work_ = &work;
    busy_ = unsigned(helpers_.size());
    failure_ = nullptr;
    ++batches_;
  }
  wake_.notify_all();
  const std::exception_ptr mine = run_catching(work);
  std::unique_lock lock(mutex_);
  done_.wait(lock, [&] { return busy_ == 0; });
  work_ = nullptr;
  if (mine) std::rethrow_exception(mine);
  if (failure_) std::rethrow_exception(failure_);
}

void QueryThreads::serve() {
  std::uint64_t served = 0;
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stopping_ || batches_ != served; });
    if (stopping_) return;
    served = batches_;
    const std::function<void()>& work = *work_;
    lock.unlock();
    const std::exception_ptr failed = run_catching(work);
    lock.lock();
    if (failed && !failure_) failure_ = failed;
    if (--busy_ == 0) done_.notify_one();
  }
}

}  // namespace eco
