// eco odometry: a scan-to-map LiDAR odometry (eco/odometry/odometry.hpp) over a sequence, with
// one map or all five on the same frames; poses, per-frame figures, accuracy against the
// reference poses and a plot of the trajectories go to --out.

#include "commands.hpp"
#include "options_file.hpp"
#include "source_flags.hpp"
#include "spellings.hpp"
#include "view_flags.hpp"

#include "bench/odometry_run.hpp"
#include "bench/sim_workload.hpp"

#include "odometry/baseline_maps.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

namespace eco::cli {
namespace {

struct OdometryOptions {
  std::string out = "results/odometry";
  std::size_t frames = 0;
  std::uint64_t seed = 1;
  double speed = sim::SimConfig{}.speed;  // the simulator's, without --data
  bool rolling_sweep = false;
  std::string map = "eco";
  odometry::OdometryConfig config;
};

nlohmann::json options_json(const OdometryOptions& o, const SourceFlags& source) {
  const odometry::OdometryConfig& c = o.config;
  nlohmann::json out{{"frames", o.frames}, {"seed", o.seed}, {"map", o.map}, {"max-range", c.max_range},
                     {"min-range", c.min_range}, {"voxel-size", c.voxel_size},
                     {"max-points-per-voxel", c.max_points_per_voxel}, {"box-side", c.box_side},
                     {"neighbours", c.neighbours}, {"max-iterations", c.max_iterations}, {"threads", c.threads},
                     {"deskew", c.deskew}, {"speed", o.speed}, {"rolling-sweep", o.rolling_sweep}};
  source.add_to(out);
  return out;
}

std::string describe(const odometry::OdometryConfig& c) {
  char text[320];
  std::snprintf(text, sizeof text,
                "range %.1f-%.1f m; map: %u points per %.2f m voxel, in a %.0f m cube, fed the scan at %.2f m;\n"
                "registration: point-to-plane on %.2f m voxels, k = %zu, %u thread(s)",
                c.min_range, c.max_range, c.max_points_per_voxel, c.voxel_size, c.box_side, 0.5 * c.voxel_size,
                1.5 * c.voxel_size, c.neighbours, c.threads);
  return text;
}

/// A registered scan with fewer of its points on the map's planes than this is taken as lost:
/// a tracked frame has over half (the simulator, KITTI), a lost one a few per cent.
constexpr double kLostFit = 0.25;

/// The odometry's map after frame `f`, as the viewer shows it.
void record_frame(view::Recorder& recorder, const odometry::Odometry& odo, const odometry::FrameReport& f,
                  const std::optional<Eigen::Vector3d>& reference) {
  std::vector<HeldPoint> held;
  for (const Eigen::Vector3d& p : odo.map().points()) held.push_back({p, {}});
  view::FrameFigures figures{f.scan_points, 0, 0, 0, f.map_points, f.update_ms, {}};
  if (odo.map().name() == "eco_ball") figures.region.radius = odo.config().map_settings().ball_radius;
  recorder.record(std::uint32_t(f.index), f.pose, held, view::occupied_voxels(held, odo.config().voxel_size), figures,
                  reference);
}

int run(OdometryOptions o, const SourceFlags& data, const ViewFlags& viewing, const std::string& command_line) {
  o.config.validate();
  std::unique_ptr<workloads::Workload> scans;
  std::vector<Eigen::Isometry3d> reference;
  bench::PoseOutput pose_output;
  std::string source;
  if (data.data.empty()) {
    sim::SimConfig sim;
    sim.seed = o.seed;
    sim.frames = data.options.start + (o.frames > 0 ? o.frames : 300);
    sim.speed = o.speed;
    sim.lidar.rolling_sweep = o.rolling_sweep;
    scans = data.from_start(std::make_unique<bench::SimWorkload>(sim));
    for (std::size_t t = 0; t < scans->size(); ++t) reference.push_back(scans->pose(t));
    source = "the simulated drive (seed " + std::to_string(o.seed) + (o.rolling_sweep ? ", rolling sweep" : "") + ")";
  } else {
    workloads::OpenedSource opened = data.open();
    std::printf("%s\n", opened.description.c_str());
    scans = std::move(opened.frames);
    if (opened.has_poses) {
      for (std::size_t t = 0; t < scans->size(); ++t) reference.push_back(scans->pose(t));
    }
    pose_output.velo_to_cam = opened.velo_to_cam;
    source = std::filesystem::path(data.data).filename().string();
    if (source.empty()) source = data.data;
  }
  const std::size_t frames = o.frames > 0 ? std::min(o.frames, scans->size()) : scans->size();
  reference.resize(std::min(reference.size(), frames));
  const std::vector<std::string> maps =
      o.map == "all" ? odometry::all_local_map_names() : std::vector<std::string>{o.map};
  for (const std::string& m : maps) (void)bench::map_is_exact(m, o.config);  // names checked first

  write_options_file(o.out, "odometry", command_line, options_json(o, data), nullptr);
  std::printf("odometry on %s, %zu frames, map%s %s\n%s\n", source.c_str(), frames, maps.size() > 1 ? "s" : "",
              o.map.c_str(), describe(o.config).c_str());
  if (reference.empty()) std::printf("no reference poses: the run gives no accuracy figures\n");
  std::fflush(stdout);  // the settings before the progress (on stderr), also into a pipe
  // the first map's run is recorded (in its child process) and, with --view, served from here
  const std::filesystem::path shown_folder = std::filesystem::path(o.out) / maps.front();
  view::RunInfo shown{"odometry on " + maps.front() + ", " + source, o.config.box_side, o.config.voxel_size,
                      frames, !reference.empty(), false};
  if (maps.front() == "eco_ball") shown.region = RegionShape::Ball;
  LiveView live(viewing, shown_folder.string(), (shown_folder / "view").string(), shown);
  const std::size_t step = std::max<std::size_t>(1, frames / 10);
  bool lost = false;  // said once a spell (in each map's process: the flag is forked with it)
  const auto observe = [&](const std::string& map, const odometry::Odometry& odo, const odometry::FrameReport& f) {
    const std::size_t t = f.index;
    const bool fits = !f.registered || f.source == 0 || double(f.inliers) >= kLostFit * double(f.source);
    if (!fits && !lost) {
      std::fprintf(stderr, "\neco odometry: %s, frame %zu: only %.0f %% of the scan lies on the map's surfaces: the track "
                           "is likely lost here (a turn or jump the motion model missed, or too little structure)\n",
                   map.c_str(), t, 100.0 * double(f.inliers) / double(f.source));
    }
    lost = !fits;
    if (t % step == step - 1 || t + 1 == frames) {
      std::fprintf(stderr, "\r%-10s frame %zu / %zu", map.c_str(), t + 1, frames);
      if (t + 1 == frames) std::fprintf(stderr, "\n");
    }
    if (live.recorder() && map == maps.front()) {
      record_frame(*live.recorder(), odo, f, t < reference.size() ? std::optional<Eigen::Vector3d>(reference[t].translation()) : std::nullopt);
      live.pace();
    }
  };
  const std::vector<bench::OdometryRun> runs = bench::run_odometry(*scans, frames, maps, o.config, reference, observe);
  std::printf("\n%s\nresults (every figure: summary.md; trajectory.svg): %s\n",
              bench::write_odometry_results(o.out, source, runs, reference, pose_output).c_str(), o.out.c_str());
  if (live.recorder()) std::printf("recorded for eco view: %s\n", shown_folder.c_str());
  std::fflush(stdout);
  live.linger();
  return 0;
}

}  // namespace

Run add_odometry(CLI::App& app, const std::string& command_line) {
  auto o = std::make_shared<OdometryOptions>();
  odometry::OdometryConfig& c = o->config;
  CLI::App* cmd = app.add_subcommand("odometry", "A LiDAR odometry on ECO's map (or another), against reference poses");
  auto data = std::make_shared<SourceFlags>(*cmd, "a simulated drive");
  data->options.place_points = false;  // the odometry deskews by its own motion: the data's poses are only a reference
  cmd->add_option("--frames", o->frames, "frames to run (0 = all; 300 for the simulator)")->capture_default_str();
  cmd->add_option("--out", o->out, "folder for the results")->capture_default_str();
  cmd->add_option("--seed", o->seed, "the simulator's seed without --data")->capture_default_str();
  cmd->add_option("--speed", o->speed, "[m/s] the simulator's vehicle, without --data")->capture_default_str();
  cmd->add_option(both_spellings("--rolling-sweep"), o->rolling_sweep,
                  "the simulator's LiDAR fires its columns over the frame: a smeared scan with per-point times")
      ->capture_default_str();
  cmd->add_option("--deskew", c.deskew, "correct each scan for the motion during its sweep, when the data times its points")
      ->capture_default_str();
  std::vector<std::string> names = odometry::all_local_map_names();
  names.push_back("all");
  cmd->add_option("--map", o->map, "the map registered against (eco_ball: ECO holding a ball of --max-range, as KISS-ICP's map), or all on the same frames")
      ->check(CLI::IsMember(names))
      ->capture_default_str();
  cmd->add_option(both_spellings("--max-range"), c.max_range, "[m] farther returns are dropped")->capture_default_str();
  cmd->add_option(both_spellings("--min-range"), c.min_range, "[m] nearer returns are dropped")->capture_default_str();
  cmd->add_option(both_spellings("--voxel-size"), c.voxel_size, "[m] the map's voxel; the scan goes in at half, is registered at 1.5x")
      ->capture_default_str();
  cmd->add_option(both_spellings("--max-points-per-voxel"), c.max_points_per_voxel, "the map's density cap")->capture_default_str();
  cmd->add_option(both_spellings("--box-side"), c.box_side, "[m] side of the cube the map holds around the sensor")
      ->capture_default_str();
  cmd->add_option("--neighbours", c.neighbours, "k: map points each plane is fitted to")->capture_default_str();
  cmd->add_option(both_spellings("--max-iterations"), c.max_iterations, "ICP iterations at most")->capture_default_str();
  cmd->add_option("--threads", c.threads, "threads ECO's batch KNN spreads the queries over")->capture_default_str();
  auto viewing = std::make_shared<ViewFlags>(*cmd);
  auto file = std::make_shared<OptionsFile>(*cmd, "odometry");
  cmd->footer(
      "Writes <out>/<map>/poses.txt (KITTI format: camera-0 poses when the folder has calib.txt) and\n"
      "frames.csv, then summary.md, summary.json, trajectory.svg and config.json. Without poses.txt the\n"
      "run goes on, without accuracy figures. Defaults are KISS-ICP's for a 100 m LiDAR (voxel = range / 100).\n"
      "--record (and --view) record the first map's run for eco view into <out>/<map>/view.\n"
      "Examples:\n"
      "  eco odometry --frames 200 --map all                 five maps on the simulator's drive\n"
      "  eco odometry --data ../shared/data/kitti_mini_00 --map all --out results/odometry00\n"
      "  eco odometry --data ../shared/data/balm2_realworld_f20-99 --max-range 40 --voxel-size 0.4\n"
      "  eco odometry --frames 200 --view                   watch the first map's run in a browser as it goes");
  return [o, data, file, viewing, command_line] {
    file->load();
    return run(*o, *data, *viewing, command_line);
  };
}

}  // namespace eco::cli
