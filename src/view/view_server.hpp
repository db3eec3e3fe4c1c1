#pragma once
// The viewer's HTTP server (cpp-httplib): the page, Debian's three.js, the recording's index and
// frames, and the run folder's files — nothing else. Every refused request gets 404 and a line on
// stderr. Routes (docs/viewer.md):
//   /, /index.html, /viewer.js, /viewer.css   the page (page_files.hpp)
//   /three/three.min.js, /three/OrbitControls.js   from libjs-three
//   /api/run                 run.json and frames.csv as one JSON object (read anew each time)
//   /api/frame?n=N&budget=B  frame N thinned to B held points (display_frame.hpp); 422 with the
//                            reason as text when its file is damaged
//   /run/<path>              a file under the run folder, symlinks resolved and kept inside it

#include <memory>
#include <string>
#include <thread>

namespace httplib {
class Server;
}

namespace eco::view {

struct ServerOptions {
  std::string host = "127.0.0.1";  ///< loopback only unless asked
  int port = 8080;                 ///< 0: any free port
  std::size_t budget = 150000;     ///< held points drawn a frame when the page does not say
  std::string three_dir = "/usr/share/javascript/three";  ///< libjs-three's files
};

/// The folder holding a recording: `run_folder`/view, or `run_folder` itself when it is one.
/// Throws std::runtime_error naming the folder when it does not exist or holds no recording.
[[nodiscard]] std::string recording_folder(const std::string& run_folder);

class ViewServer {
 public:
  /// Serves the run in `run_folder` (its recording: recording_folder()). Throws
  /// std::runtime_error naming the folder, or the host and port that cannot be bound.
  ViewServer(const std::string& run_folder, const ServerOptions& options);
  ~ViewServer();  ///< stops serving
  ViewServer(const ViewServer&) = delete;
  ViewServer& operator=(const ViewServer&) = delete;

  [[nodiscard]] int port() const { return port_; }
  [[nodiscard]] std::string url() const;
  /// Serves until the process is ended (Ctrl-C, SIGTERM).
  void serve_forever() const;

 private:
  void route();

  std::string root_;       // the run folder, canonical
  std::string recording_;  // its recording folder, canonical
  ServerOptions options_;
  std::unique_ptr<httplib::Server> server_;
  int port_ = 0;
  std::thread listener_;
};

}  // namespace eco::view
