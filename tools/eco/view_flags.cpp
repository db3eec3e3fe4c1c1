// The flags, the recorder and the live server of a run.

#include "view_flags.hpp"

#include <cstdio>
#include <thread>

namespace eco::cli {

ViewFlags::ViewFlags(CLI::App& cmd) {
  cmd.add_flag("--record", record, "write what `eco view` shows, a file a frame, into <out>/view");
  cmd.add_flag("--view", view, "serve the run to a browser while it computes (implies --record), then until Ctrl-C");
  cmd.add_option("--host", server.host, "address --view listens on (127.0.0.1: this machine only)")->capture_default_str();
  cmd.add_option("--port", server.port, "port --view listens on (0: any free one)")->capture_default_str();
  cmd.add_option("--pace", pace, "[s] spend at least this long a frame, so a browser can follow")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
}

LiveView::LiveView(const ViewFlags& flags, const std::string& run_folder, const std::string& folder,
                   const view::RunInfo& info)
    : flags_(flags) {
  if (!flags.recording()) return;
  recorder_ = std::make_unique<view::Recorder>(folder, info);
  if (!flags.view) return;
  server_ = std::make_unique<ServerProcess>(run_folder, flags.server);
  std::printf("viewer: %s (live; Ctrl-C ends it)\n", server_->url().c_str());
  std::fflush(stdout);
}

void LiveView::pace() {
  const auto until = last_ + std::chrono::duration<double>(flags_.pace);
  std::this_thread::sleep_until(until);
  last_ = std::chrono::steady_clock::now();
}

void LiveView::linger() {
  if (!server_) return;
  std::printf("viewer: the run is done; still serving %s until Ctrl-C\n", server_->url().c_str());
  std::fflush(stdout);
  server_->wait();
}

}  // namespace eco::cli
