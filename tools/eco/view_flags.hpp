#pragma once
// --record and --view, shared by `eco run` and `eco odometry`: what the viewer needs, written per
// frame into <out>/view, and, with --view, served while the run computes.

#include "server_process.hpp"

#include "view/recorder.hpp"

#include <CLI/CLI.hpp>

#include <chrono>
#include <memory>
#include <string>

namespace eco::cli {

struct ViewFlags {
  bool record = false;
  bool view = false;       // implies record
  view::ServerOptions server;
  double pace = 0.0;       // [s] a frame at least, so that a watcher can follow

  explicit ViewFlags(CLI::App& cmd);
  [[nodiscard]] bool recording() const { return record || view; }
};

/// The recording of a run and, with --view, its server (in a process of its own): made before the
/// first frame.
class LiveView {
 public:
  /// Records into `folder` when the flags ask for it (else does nothing), and serves `run_folder`.
  LiveView(const ViewFlags& flags, const std::string& run_folder, const std::string& folder, const view::RunInfo& info);
  /// The recorder, or null without --record / --view.
  [[nodiscard]] view::Recorder* recorder() { return recorder_.get(); }
  /// Waits out the rest of --pace since the last call.
  void pace();
  /// With --view: says so and serves until Ctrl-C.
  void linger();

 private:
  const ViewFlags& flags_;
  std::unique_ptr<view::Recorder> recorder_;
  std::unique_ptr<ServerProcess> server_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace eco::cli
