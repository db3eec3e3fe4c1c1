// Children forked without exec: fork_alone refuses while another thread runs (the fault that hung
// `eco odometry --view` under AddressSanitizer, made certain instead of one run in four), and
// QueryThreads serve a process forked beside their helpers (as Python's multiprocessing does)
// with helpers of its own, answering as in the parent.

#include "bench/fork_alone.hpp"

#include <eco/query_threads.hpp>

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>

namespace eco::bench {
namespace {

/// The child's exit code; a child still running after a minute is killed and counts as hung (-1).
int exit_code_of(pid_t child) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::minutes(1);
  int status = 0;
  while (waitpid(child, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > give_up) {
      kill(child, SIGKILL);
      waitpid(child, &status, 0);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -2;
}

/// The distinct threads that ran one batch on `threads`.
std::size_t threads_in_a_batch(QueryThreads& threads) {
  std::mutex mutex;
  std::set<std::thread::id> seen;
  threads.run([&] {
    const std::lock_guard lock(mutex);
    seen.insert(std::this_thread::get_id());
  });
  return seen.size();
}

TEST(ForkAlone, CountsTheThreadsThatRun) {
  ASSERT_EQ(threads_in_this_process(), 1u);
  const QueryThreads threads(3);
  EXPECT_EQ(threads_in_this_process(), 3u);
}

TEST(ForkAlone, RefusesBesideAnotherThread) {
  const QueryThreads threads(2);  // one helper, waiting for a batch
  try {
    (void)fork_alone();
    FAIL() << "forked beside a running thread";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("runs 2 threads"), std::string::npos) << e.what();
  }
}

TEST(ForkAlone, ForksOnceTheOtherThreadsAreJoined) {
  { const QueryThreads threads(2); }  // started and joined: gone from the task list
  const pid_t child = fork_alone();
  if (child == 0) _exit(threads_in_this_process() == 1 ? 7 : 1);
  EXPECT_EQ(exit_code_of(child), 7);
}

TEST(QueryThreadsAfterFork, TheChildStartsHelpersOfItsOwn) {
  QueryThreads threads(2);
  ASSERT_EQ(threads_in_a_batch(threads), 2u);
  const pid_t child = fork();  // beside the idle helper, as a Python program's multiprocessing does
  ASSERT_GE(child, 0);
  if (child == 0) {
    // the parent's helper is not here: a batch waiting for it would hang
    const bool both = threads_in_a_batch(threads) == 2 && threads_in_a_batch(threads) == 2;
    _exit(both && threads_in_this_process() == 2 ? 0 : 1);  // no destructors: the test's process is the parent's
  }
  EXPECT_EQ(exit_code_of(child), 0) << "-1: the child hung";
  EXPECT_EQ(threads_in_a_batch(threads), 2u) << "the parent's helper after the fork";
}

TEST(QueryThreadsAfterFork, ThreadsOfTheChildRaceToStartOneCrew) {
  QueryThreads threads(2);
  ASSERT_EQ(threads_in_a_batch(threads), 2u);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::atomic<std::size_t> ran{0};
    const auto batch = [&] { threads.run([&] { ++ran; }); };
    std::thread other(batch);
    batch();
    other.join();
    _exit(ran == 4 ? 0 : 1);  // each batch on its caller and one helper
  }
  EXPECT_EQ(exit_code_of(child), 0) << "-1: the child hung";
}

}  // namespace
}  // namespace eco::bench
