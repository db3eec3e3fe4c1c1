// eco view: serves a recorded run (eco run --record, eco odometry --record) to a browser.

#include "commands.hpp"
#include "server_process.hpp"

#include "view/run_index.hpp"
#include "view/view_server.hpp"

#include <cstdio>
#include <memory>

namespace eco::cli {

Run add_view(CLI::App& app, const std::string&) {
  auto folder = std::make_shared<std::string>();
  auto options = std::make_shared<view::ServerOptions>();
  auto parent = std::make_shared<pid_t>(0);
  CLI::App* cmd = app.add_subcommand("view", "Serve a recorded run to a web browser: the moving box, frame by frame");
  cmd->add_option("RUN_DIR", *folder, "the --out folder of eco run --record (or of eco odometry --record's map)")
      ->required();
  cmd->add_option("--host", options->host, "address to listen on (127.0.0.1: this machine only)")->capture_default_str();
  cmd->add_option("--port", options->port, "port to listen on (0: any free one)")->capture_default_str();
  cmd->add_option("--budget", options->budget,
                  "held points drawn a frame at most: beyond it the server keeps every k-th (the page may ask for another)")
      ->capture_default_str();
  cmd->add_option("--child-of", *parent, "serve for --view's process PID: end with it, print the address alone")
      ->group("");  // hidden: the run's own server process (server_process.hpp)
  cmd->footer(
      "Serves the page, three.js (Debian's libjs-three) and the files under RUN_DIR, nothing else.\n"
      "Examples:\n"
      "  eco run --frames 60 --record --out results/run && eco view results/run\n"
      "  eco view results/odometry/eco --port 0           any free port; the address is printed");
  return [folder, options, parent] {
    if (*parent != 0 && !follow_parent(*parent)) return 1;
    const view::ViewServer server(*folder, *options);
    if (*parent != 0) {
      std::printf("%s\n", server.url().c_str());
      std::fflush(stdout);
      server.serve_forever();
    }
    const view::Index index = view::read_index(view::recording_folder(*folder) + "/" + view::kIndexFile);
    std::printf("viewer: %s serving %s, %zu frames (Ctrl-C ends it)\n", server.url().c_str(), folder->c_str(),
                index.rows.size());
    if (!index.error.empty()) std::printf("viewer: %s\n", index.error.c_str());
    std::fflush(stdout);
    server.serve_forever();
    return 0;
  };
}

}  // namespace eco::cli
