// The routes of view_server.hpp, and the one rule for files: a request names a file only if its
// resolved path (symlinks followed) lies inside the folder it was asked of.

#include "view/view_server.hpp"

#include "view/display_frame.hpp"
#include "view/frame_file.hpp"
#include "view/page_files.hpp"
#include "view/run_index.hpp"

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include <unistd.h>

namespace eco::view {
namespace {

namespace fs = std::filesystem;

void log_refusal(const httplib::Request& request, const std::string& why) {
  std::fprintf(stderr, "eco view: 404 for %s %s (%s)\n", request.method.c_str(), request.path.c_str(), why.c_str());
}

void not_found(const httplib::Request& request, httplib::Response& response, const std::string& why) {
  log_refusal(request, why);
  response.status = 404;
  response.set_content("404: " + why + "\n", "text/plain; charset=utf-8");
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

/// `relative` under `folder` when it resolves inside it (symlinks followed), else nullopt.
std::optional<fs::path> inside(const fs::path& folder, const std::string& relative) {
  if (relative.empty() || relative.front() == '/' || relative.find('\0') != std::string::npos) return std::nullopt;
  const fs::path asked(relative);
  for (const fs::path& part : asked) {
    if (part == "..") return std::nullopt;
  }
  std::error_code error;
  const fs::path resolved = fs::canonical(folder / asked, error);
  if (error) return std::nullopt;
  const auto [folder_end, unused] = std::mismatch(folder.begin(), folder.end(), resolved.begin(), resolved.end());
  if (folder_end != folder.end() || !fs::is_regular_file(resolved)) return std::nullopt;
  return resolved;
}

std::string content_type_of(const fs::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".json") return "application/json";
  if (ext == ".csv" || ext == ".md" || ext == ".txt") return "text/plain; charset=utf-8";
  if (ext == ".svg") return "image/svg+xml";
  return "application/octet-stream";
}

/// run.json and frames.csv, column by column.
nlohmann::json run_json(const fs::path& recording) {
  nlohmann::json out;
  std::ifstream run(recording / kRunFile);
  out["run"] = nlohmann::json::parse(run, nullptr, false);
  if (out["run"].is_discarded()) out["run"] = nlohmann::json::object();
  const Index index = read_index((recording / kIndexFile).string());
  nlohmann::json columns{{"frame", nlohmann::json::array()}, {"x", nlohmann::json::array()},
                         {"y", nlohmann::json::array()},     {"z", nlohmann::json::array()},
                         {"ref", nlohmann::json::array()},   {"scan", nlohmann::json::array()},
                         {"inserted", nlohmann::json::array()}, {"pruned", nlohmann::json::array()},
                         {"cleared", nlohmann::json::array()}, {"held", nlohmann::json::array()},
                         {"update_ms", nlohmann::json::array()}, {"region", nlohmann::json::array()}};
  for (const IndexRow& row : index.rows) {
    columns["frame"].push_back(row.frame);
    columns["x"].push_back(row.sensor.x());
    columns["y"].push_back(row.sensor.y());
    columns["z"].push_back(row.sensor.z());
    columns["ref"].push_back(row.reference ? nlohmann::json{row.reference->x(), row.reference->y(), row.reference->z()}
                                           : nlohmann::json(nullptr));
    columns["scan"].push_back(row.figures.scan);
    columns["inserted"].push_back(row.figures.inserted);
    columns["pruned"].push_back(row.figures.pruned);
    columns["cleared"].push_back(row.figures.cleared);
    columns["held"].push_back(row.figures.held);
    columns["update_ms"].push_back(row.figures.update_ms);
    const RegionExtents& r = row.figures.region;
    columns["region"].push_back({r.radius, r.ahead, r.behind, r.left, r.right, r.up, r.down});
  }
  out["frames"] = std::move(columns);
  out["error"] = index.error;
  return out;
}

/// A non-negative integer query parameter, or `fallback` when absent; nullopt when malformed.
std::optional<std::size_t> count_parameter(const httplib::Request& request, const char* name, std::size_t fallback) {
  if (!request.has_param(name)) return fallback;
  const std::string text = request.get_param_value(name);
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  return std::stoul(text);
}

}  // namespace

std::string recording_folder(const std::string& run_folder) {
  const fs::path folder(run_folder);
  if (!fs::is_directory(folder)) throw std::runtime_error("no run folder at " + run_folder);
  if (fs::is_regular_file(folder / "view" / kRunFile)) return (folder / "view").string();
  if (fs::is_regular_file(folder / kRunFile)) return folder.string();
  throw std::runtime_error(run_folder + " holds no recording (view/" + kRunFile +
                           "): make one with eco run --record --out " + run_folder);
}

ViewServer::ViewServer(const std::string& run_folder, const ServerOptions& options)
    : options_(options), server_(std::make_unique<httplib::Server>()) {
  std::signal(SIGPIPE, SIG_IGN);  // a browser that goes away mid-transfer fails a write, not the server
  recording_ = fs::canonical(recording_folder(run_folder)).string();
  root_ = fs::canonical(run_folder).string();
  route();
  server_->set_tcp_nodelay(true);  // a frame's header and body leave at once, not a delayed ACK apart
  port_ = options.port == 0 ? server_->bind_to_any_port(options.host)
                            : (server_->bind_to_port(options.host, options.port) ? options.port : -1);
  if (port_ < 0) {
    throw std::runtime_error("cannot serve on " + options.host + ":" + std::to_string(options.port) +
                             " (in use? try --port 0 for any free port)");
  }
  listener_ = std::thread([this] { server_->listen_after_bind(); });
}

ViewServer::~ViewServer() {
  server_->stop();
  if (listener_.joinable()) listener_.join();
}

void ViewServer::serve_forever() const {
  for (;;) pause();
}

std::string ViewServer::url() const {
  const bool v6 = options_.host.find(':') != std::string::npos;
  return "http://" + (v6 ? "[" + options_.host + "]" : options_.host) + ":" + std::to_string(port_) + "/";
}

void ViewServer::route() {
  httplib::Server& s = *server_;
  for (const PageFile& file : page_files()) {
    const auto serve = [file](const httplib::Request&, httplib::Response& response) {
      response.set_content(file.body.data(), file.body.size(), std::string(file.content_type));
    };
    s.Get(std::string(file.path), serve);
    if (file.path == "/index.html") s.Get("/", serve);
  }
  s.Get("/three/(three\\.min\\.js|OrbitControls\\.js)", [this](const httplib::Request& request, httplib::Response& response) {
    const fs::path file = fs::path(options_.three_dir) /
                          (request.matches[1] == "OrbitControls.js" ? "examples/js/controls/OrbitControls.js"
                                                                    : "build/three.min.js");
    if (!fs::is_regular_file(file)) return not_found(request, response, file.string() + " is missing: apt-get install libjs-three");
    response.set_content(read_bytes(file), "text/javascript; charset=utf-8");
  });
  s.Get("/api/run", [this](const httplib::Request&, httplib::Response& response) {
    response.set_header("Cache-Control", "no-store");
    nlohmann::json run = run_json(recording_);
    run["budget"] = options_.budget;
    response.set_content(run.dump(), "application/json");
  });
  s.Get("/api/frame", [this](const httplib::Request& request, httplib::Response& response) {
    const std::optional<std::size_t> n = count_parameter(request, "n", std::size_t(-1));
    const std::optional<std::size_t> budget = count_parameter(request, "budget", options_.budget);
    if (!n || !budget || *n == std::size_t(-1)) return not_found(request, response, "n and budget must be counts");
    const fs::path file = fs::path(recording_) / frame_file_name(std::uint32_t(*n));
    if (!fs::is_regular_file(file)) return not_found(request, response, "frame " + std::to_string(*n) + " is not recorded");
    try {
      const bool voxels = request.get_param_value("voxels") != "0";
      response.set_content(display_bytes(read_frame_file(file.string()), *budget, voxels), "application/octet-stream");
    } catch (const FrameFileError& e) {
      std::fprintf(stderr, "eco view: 422 for frame %zu: %s\n", *n, e.what());
      response.status = 422;
      response.set_content(e.what(), "text/plain; charset=utf-8");
    }
  });
  s.Get("/run/(.*)", [this](const httplib::Request& request, httplib::Response& response) {
    const std::optional<fs::path> file = inside(root_, request.matches[1]);
    if (!file) return not_found(request, response, "not a file inside the run folder");
    response.set_content(read_bytes(*file), content_type_of(*file));
  });
  s.Get(".*", [](const httplib::Request& request, httplib::Response& response) {
    not_found(request, response, "not one of the viewer's files");
  });
}

}  // namespace eco::view
