#include "bench/odometry_run.hpp"

#include "bench/fork_alone.hpp"
#include "bench/trajectory_plot.hpp"

#include <eco/io/error.hpp>
#include <eco/io/kitti.hpp>
#include "odometry/baseline_maps.hpp"

#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace eco::bench {
namespace {

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream file(path);
  file << text;
  if (!file) throw io::Error(path.string(), "", "cannot be written");
}

std::string frames_csv(const OdometryRun& run) {
  std::ostringstream csv;
  csv << "frame,registered,scan_points,dropped_invalid,dropped_range,map_input,source,iterations,correspondences,inliers,"
         "threshold_m,map_points,preprocess_ms,downsample_ms,query_ms,solve_ms,update_ms,total_ms,own_faults,"
         "map_faults\n";
  for (const odometry::FrameReport& f : run.frames) {
    csv << f.index << ',' << int(f.registered) << ',' << f.scan_points << ',' << f.dropped_invalid << ','
        << f.dropped_range << ',' << f.map_input << ',' << f.source << ',' << f.iterations << ',' << f.correspondences
        << ',' << f.inliers << ',' << f.threshold << ',' << f.map_points << ',' << f.preprocess_ms << ',' << f.downsample_ms << ','
        << f.query_ms << ',' << f.solve_ms << ',' << f.update_ms << ',' << f.total_ms << ',' << f.own_faults << ','
        << f.map_faults << '\n';
  }
  return csv.str();
}

const OdometryRun* find_run(const std::vector<OdometryRun>& runs, const std::string& map) {
  const auto it = std::ranges::find(runs, map, &OdometryRun::map);
  return it == runs.end() ? nullptr : &*it;
}

/// Room for a run's frame reports in memory shared with a child process, and for its error.
class FrameSlots {
 public:
  explicit FrameSlots(std::size_t frames) : frames_(frames), bytes_(sizeof(Header) + frames * sizeof(odometry::FrameReport)) {
    memory_ = mmap(nullptr, bytes_, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (memory_ == MAP_FAILED) throw std::runtime_error("odometry: no shared memory for " + std::to_string(frames) + " frames");
    new (memory_) Header();
  }
  FrameSlots(const FrameSlots&) = delete;
  FrameSlots& operator=(const FrameSlots&) = delete;
  ~FrameSlots() { munmap(memory_, bytes_); }

  void put(const odometry::FrameReport& report) {
    if (header().count == frames_) return;
    new (reports() + header().count++) odometry::FrameReport(report);
  }
  void fail(const char* message) { std::snprintf(header().error, sizeof header().error, "%s", message); }
  [[nodiscard]] std::vector<odometry::FrameReport> reports_copied() const {
    return {reports(), reports() + header().count};
  }
  [[nodiscard]] const char* error() const { return header().error; }

 private:
  struct alignas(64) Header {  // the reports after it aligned as Eigen's matrices want
    std::size_t count = 0;
    char error[512] = {};
  };
  [[nodiscard]] Header& header() const { return *static_cast<Header*>(memory_); }
  [[nodiscard]] odometry::FrameReport* reports() const {
    return reinterpret_cast<odometry::FrameReport*>(static_cast<std::byte*>(memory_) + sizeof(Header));
  }
  std::size_t frames_;
  std::size_t bytes_;
  void* memory_;
};

/// What `work` puts in its slots (room for `frames`), done in a child process: each map's run
/// starts from the same heap and leaves none of its own to the next, so that the page faults of
/// the odometry's own work are the map's doing alone. Throws std::runtime_error with the child's
/// message when it failed, std::logic_error when this process runs other threads (fork_alone).
std::vector<odometry::FrameReport> in_child_process(std::size_t frames, const std::function<void(FrameSlots&)>& work) {
  FrameSlots slots(frames);
  std::fflush(nullptr);
  const pid_t child = fork_alone();
  if (child == 0) {
    int status = 0;
    try {
      work(slots);
    } catch (const std::exception& e) {
      slots.fail(e.what());
      status = 1;
    }
    std::fflush(nullptr);
    _exit(status);  // no destructors, no atexit handlers: the parent's to run
  }
  int status = 0;
  waitpid(child, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error(*slots.error() ? slots.error() : "odometry: the run's process ended abnormally");
  }
  return slots.reports_copied();
}

}  // namespace

std::string brief_odometry_table(const std::vector<OdometryRun>& runs) {
  const OdometryRun* eco = find_run(runs, "eco");
  const double eco_ms = eco ? figures_of(*eco).frame_ms : 0.0;
  const bool segments = !runs.empty() && runs.front().errors && !runs.front().errors->by_length.empty();
  std::ostringstream s;
  s << "ms per frame (mean after the first); × ECO's: the frame over ECO's; map: its queries and update;\n"
    << (segments ? "drift: KITTI's mean relative translation error over 100-800 m; " : "")
    << "ATE after a rigid alignment\n\n"
    << "| map        | frame |  × ECO's | map share | update share | " << (segments ? "drift % | " : "") << "ATE m  |\n"
    << "|------------|------:|---------:|----------:|-------------:|" << (segments ? "--------:|" : "") << "-------:|\n";
  for (const OdometryRun& run : runs) {
    const OdometryFigures f = figures_of(run);
    char row[200];
    std::snprintf(row, sizeof row, "| %-10s | %5.2f | %7.2f× | %8.0f %% | %10.1f %% | ", run.map.c_str(), f.frame_ms,
                  eco_ms > 0 ? f.frame_ms / eco_ms : 0.0, f.frame_ms > 0 ? 100 * (f.query_ms + f.update_ms) / f.frame_ms : 0.0,
                  f.frame_ms > 0 ? 100 * f.update_ms / f.frame_ms : 0.0);
    s << row;
    if (segments) s << format("%7.3f", run.errors->translation_pct) << " | ";
    s << (run.errors ? format("%6.3f", run.errors->ate_rmse) : std::string("     –")) << " |\n";
  }
  return s.str();
}

OdometryFigures figures_of(const OdometryRun& run) {
  OdometryFigures f;
  std::vector<double> totals;
  for (std::size_t i = 1; i < run.frames.size(); ++i) {  // the first frame registers nothing
    const odometry::FrameReport& r = run.frames[i];
    totals.push_back(r.total_ms);
    f.own_ms += r.preprocess_ms + r.downsample_ms;
    f.query_ms += r.query_ms;
    f.solve_ms += r.solve_ms;
    f.update_ms += r.update_ms;
    f.own_faults += double(r.own_faults);
    f.map_faults += double(r.map_faults);
    f.iterations += r.iterations;
  }
  if (!run.frames.empty()) f.map_points = run.frames.back().map_points;
  if (totals.empty()) return f;
  const double n = double(totals.size());
  for (double* v : {&f.own_ms, &f.query_ms, &f.solve_ms, &f.update_ms, &f.own_faults, &f.map_faults, &f.iterations}) {
    *v /= n;
  }
  for (double t : totals) f.frame_ms += t / n;
  std::ranges::sort(totals);
  f.p99_ms = totals[std::min(totals.size() - 1, std::size_t(0.99 * n))];
  return f;
}

bool map_is_exact(const std::string& map, const odometry::OdometryConfig& config) {
  odometry::MapSettings alone = config.map_settings();
  alone.threads = 1;  // no helper started: the caller forks next
  return odometry::make_any_local_map(map, alone)->exact();
}

std::vector<OdometryRun> run_odometry(const workloads::Workload& scans, std::size_t frames,
                                      const std::vector<std::string>& maps, const odometry::OdometryConfig& config,
                                      std::span<const Eigen::Isometry3d> reference, const FrameObserver& observe) {
  frames = std::min(frames, scans.size());
  std::vector<OdometryRun> runs;
  for (const std::string& map : maps) {
    OdometryRun run;
    run.map = map;
    run.exact = map_is_exact(map, config);
    run.frames = in_child_process(frames, [&](FrameSlots& slots) {
      odometry::Odometry odo(config, odometry::make_any_local_map(map, config.map_settings()));
      if (!reference.empty()) odo.set_start(reference.front());
      for (std::size_t t = 0; t < frames; ++t) {
        const workloads::WorkloadFrame frame = scans.frame(t);
        const odometry::FrameReport report = odo.register_frame(ScanView(frame.points), frame.point_times);
        slots.put(report);
        if (observe) observe(map, odo, report);
      }
    });
    for (const odometry::FrameReport& f : run.frames) run.poses.push_back(f.pose);
    if (!reference.empty() && frames >= 2) {
      run.errors = odometry::trajectory_errors(run.poses, reference.first(frames));
    }
    runs.push_back(std::move(run));
  }
  return runs;
}

std::string write_odometry_results(const std::filesystem::path& out, const std::string& source,
                                   const std::vector<OdometryRun>& runs, std::span<const Eigen::Isometry3d> reference,
                                   const PoseOutput& poses) {
  std::filesystem::create_directories(out);
  for (const OdometryRun& run : runs) {
    std::filesystem::create_directories(out / run.map);
    std::vector<Eigen::Isometry3d> written = run.poses;
    if (poses.velo_to_cam) {
      for (Eigen::Isometry3d& p : written) p = *poses.velo_to_cam * p * poses.velo_to_cam->inverse();
    }
    io::write_kitti_poses(out / run.map / "poses.txt", written);
    write_text(out / run.map / "frames.csv", frames_csv(run));
  }

  const OdometryRun* eco = find_run(runs, "eco");
  const double eco_ms = eco ? figures_of(*eco).frame_ms : 0.0;
  std::ostringstream md;
  nlohmann::json json{{"source", source}, {"maps", nlohmann::json::array()}};
  md << "# Odometry on " << source << ", " << (runs.empty() ? 0 : runs.front().frames.size()) << " frames\n\n"
     << "Per frame after the first, in ms. Own work: the odometry's range filter and voxel downsampling "
        "(which allocate); map share: (queries + update) / frame.\n\n"
     << "| map | exact | frame | × ECO's | p99 / mean | own work | own faults | map faults | queries | update "
        "| map share | update share | iterations | map points |\n"
     << "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const OdometryRun& run : runs) {
    const OdometryFigures f = figures_of(run);
    const double share = f.frame_ms > 0 ? (f.query_ms + f.update_ms) / f.frame_ms : 0.0;
    const double update_share = f.frame_ms > 0 ? f.update_ms / f.frame_ms : 0.0;
    md << "| " << run.map << " | " << (run.exact ? "yes" : "no") << " | " << format("%.2f", f.frame_ms) << " | "
       << (eco_ms > 0 ? format("%.2f×", f.frame_ms / eco_ms) : "–") << " | "
       << format("%.2f", f.frame_ms > 0 ? f.p99_ms / f.frame_ms : 0.0) << " | " << format("%.2f", f.own_ms) << " | "
       << format("%.0f", f.own_faults) << " | " << format("%.0f", f.map_faults) << " | " << format("%.2f", f.query_ms)
       << " | " << format("%.2f", f.update_ms) << " | " << format("%.0f %%", 100 * share) << " | "
       << format("%.1f %%", 100 * update_share) << " | " << format("%.1f", f.iterations) << " | " << f.map_points
       << " |\n";
    nlohmann::json m{{"map", run.map},           {"exact", run.exact},          {"frame_ms", f.frame_ms},
                     {"p99_ms", f.p99_ms},       {"own_ms", f.own_ms},          {"own_faults", f.own_faults},
                     {"map_faults", f.map_faults}, {"query_ms", f.query_ms},    {"solve_ms", f.solve_ms},
                     {"update_ms", f.update_ms}, {"iterations", f.iterations},  {"map_points", f.map_points}};
    if (run.errors) {
      const odometry::TrajectoryErrors& e = *run.errors;
      m["errors"] = {{"path_length_m", e.path_length},   {"translation_pct", e.translation_pct},
                     {"rotation_deg_per_100m", e.rotation_deg_per_100m}, {"segments", e.by_length.size()},
                     {"ate_rmse_m", e.ate_rmse},         {"rpe_translation_rmse_m", e.rpe_translation_rmse},
                     {"rpe_rotation_rmse_deg", e.rpe_rotation_rmse_deg}};
    }
    json["maps"].push_back(m);
  }
  if (!reference.empty() && !runs.empty() && runs.front().errors) {
    const odometry::TrajectoryErrors& first = *runs.front().errors;
    md << "\nAgainst the reference poses (" << format("%.0f m", first.path_length) << " driven). KITTI's relative "
       << "errors are the mean over 100–800 m segments"
       << (first.by_length.empty() ? ": the drive is too short for any, so only ATE and RPE are given" : "")
       << ".\n\n| map | translation % | rotation °/100 m | ATE m | RPE translation m | RPE rotation ° |\n"
       << "|---|--:|--:|--:|--:|--:|\n";
    for (const OdometryRun& run : runs) {
      const odometry::TrajectoryErrors& e = *run.errors;
      const bool segments = !e.by_length.empty();
      md << "| " << run.map << " | " << (segments ? format("%.3f", e.translation_pct) : "–") << " | "
         << (segments ? format("%.4f", e.rotation_deg_per_100m) : "–") << " | " << format("%.4f", e.ate_rmse) << " | "
         << format("%.4f", e.rpe_translation_rmse) << " | " << format("%.4f", e.rpe_rotation_rmse_deg) << " |\n";
    }
  } else {
    md << "\nNo reference poses: no accuracy figures.\n";
  }
  write_text(out / "summary.md", md.str());
  write_text(out / "summary.json", json.dump(2) + "\n");
  write_trajectory_plot(out / "trajectory.svg", source, runs, reference);
  return brief_odometry_table(runs);
}

}  // namespace eco::bench
