#include "server_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

extern char** environ;

namespace eco::cli {
namespace {

std::runtime_error failure(const std::string& what) {
  return std::runtime_error("viewer: " + what + ": " + std::strerror(errno));
}

/// The line the child writes first (its URL), or "" when it ends without one.
std::string first_line(int fd) {
  std::string line;
  char c = 0;
  for (;;) {
    const ssize_t got = read(fd, &c, 1);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0 || c == '\n') return line;
    line += c;
  }
}

}  // namespace

ServerProcess::ServerProcess(const std::string& run_folder, const view::ServerOptions& options) {
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  std::vector<std::string> args{"eco", "view", run_folder, "--host", options.host, "--port", std::to_string(options.port),
                                "--budget", std::to_string(options.budget), "--child-of", std::to_string(getpid())};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  int url_pipe[2];
  if (pipe2(url_pipe, O_CLOEXEC) != 0) throw failure("no pipe for the server's address");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, url_pipe[1], STDOUT_FILENO);  // its stdout: the URL alone
  const int spawned = posix_spawn(&pid_, self.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(url_pipe[1]);
  if (spawned != 0) {
    close(url_pipe[0]);
    errno = spawned;
    throw failure("cannot start " + self + " view");
  }
  url_ = first_line(url_pipe[0]);
  close(url_pipe[0]);
  if (url_.empty()) {
    wait();
    throw std::runtime_error("viewer: the server ended before serving (its reason is above)");
  }
}

ServerProcess::~ServerProcess() {
  if (pid_ <= 0) return;
  kill(pid_, SIGTERM);
  wait();
}

void ServerProcess::wait() {
  while (pid_ > 0 && waitpid(pid_, nullptr, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
}

bool follow_parent(pid_t parent) {
  prctl(PR_SET_PDEATHSIG, SIGTERM);
  return getppid() == parent;  // after the request: a parent gone before it would send nothing
}

}  // namespace eco::cli
