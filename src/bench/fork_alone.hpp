#pragma once
// fork() for a child that goes on running our code (allocating, logging, running a map) without
// exec: allowed only while the process has one thread. A child forked beside other threads holds
// their locks as they were at the fork (the allocator's, a logger's, a server's) with nobody left
// to release them; glibc's malloc happens to survive it, AddressSanitizer's does not.

#include <sys/types.h>

#include <cstddef>

namespace eco::bench {

/// The threads this process runs now, the calling one counted (/proc/self/task).
[[nodiscard]] std::size_t threads_in_this_process();

/// fork(), refused with std::logic_error (naming the count) while any other thread runs, and with
/// std::runtime_error when the system refuses it.
[[nodiscard]] pid_t fork_alone();

}  // namespace eco::bench
