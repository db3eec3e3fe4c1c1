#include "bench/fork_alone.hpp"

#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>

namespace eco::bench {

std::size_t threads_in_this_process() {
  std::size_t count = 0;
  for ([[maybe_unused]] const auto& task : std::filesystem::directory_iterator("/proc/self/task")) ++count;
  return count;
}

pid_t fork_alone() {
  // a thread just joined leaves the task list a moment after its join returns: wait that out,
  // never a thread that still runs (it stays listed, and the fork is refused)
  std::size_t threads = threads_in_this_process();
  for (int wait = 0; threads != 1 && wait < 100; ++wait) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    threads = threads_in_this_process();
  }
  if (threads != 1) {
    throw std::logic_error("fork refused: this process runs " + std::to_string(threads) +
                           " threads, and a child forked beside them may wait forever on a lock one held");
  }
  const pid_t child = fork();
  if (child < 0) throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
  return child;
}

}  // namespace eco::bench
