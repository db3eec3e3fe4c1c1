#pragma once
// `eco view` of a run folder in a process of its own, for `--view`: started by posix_spawn of
// this executable (nothing forked beside threads), so that the server's threads and heap stay out
// of the run's process, which forks each odometry map's child and times the updates.

#include "view/view_server.hpp"

#include <sys/types.h>

#include <string>

namespace eco::cli {

class ServerProcess {
 public:
  /// Starts `eco view run_folder` with `options` and waits until it serves. Throws
  /// std::runtime_error when it cannot start or ends before serving (its reason on stderr).
  ServerProcess(const std::string& run_folder, const view::ServerOptions& options);
  /// Ends it (SIGTERM) and waits for it. It also ends when this process does, however that ends.
  ~ServerProcess();
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;

  [[nodiscard]] const std::string& url() const { return url_; }
  /// Waits until the server ends (Ctrl-C reaches both processes).
  void wait();

 private:
  pid_t pid_ = -1;
  std::string url_;
};

/// What `eco view --child-of PID` does first: ends with PID (SIGTERM when it dies), and returns
/// false when PID is already gone.
[[nodiscard]] bool follow_parent(pid_t parent);

}  // namespace eco::cli
