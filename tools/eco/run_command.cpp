// eco run: streams a sequence's raw scans through ECO, printing per-frame figures and, when
// asked, writing the held points and the voxel map as PLY.

#include "commands.hpp"
#include "spellings.hpp"
#include "config_options.hpp"
#include "options_file.hpp"
#include "source_flags.hpp"
#include "view_flags.hpp"

#include "bench/sim_workload.hpp"
#include "bench/stopwatch.hpp"
#include "bench/trails.hpp"

#include <eco/eco.hpp>
#include <eco/io/ply.hpp>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

namespace eco::cli {
namespace {

struct RunOptions {
  std::string out = "results/run";
  std::size_t frames = 0;
  std::size_t export_every = 0;
  double voxel = 0.1;
  std::uint64_t seed = 1;
  Config config;  // the library's defaults
  std::string save;             // the map written here after the last frame (and every save_every)
  std::size_t save_every = 0;
  std::string load;             // a saved map to go on from
};

/// Where --save-every writes without --save.
std::string save_path(const RunOptions& o) {
  return o.save.empty() ? (std::filesystem::path(o.out) / "map.eco").string() : o.save;
}

/// `points` minus `origin`, as float32 (PLY): near the origin, millimetres survive the cast.
io::PointCloud cloud_of(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& origin) {
  io::PointCloud cloud;
  for (const Eigen::Vector3d& p : points) cloud.points.push_back((p - origin).cast<float>());
  return cloud;
}

void export_frame(const RunOptions& o, const EgoOctree& tree, std::size_t t) {
  char stem[32];
  std::snprintf(stem, sizeof stem, "%06zu", t);
  const std::filesystem::path folder(o.out);
  std::filesystem::create_directories(folder);
  // Ego frame, so float32 PLY keeps millimetres however far the drive went.
  const Eigen::Vector3d sensor = tree.pose().translation();
  io::write_ply(folder / (std::string(stem) + "_points.ply"), cloud_of(tree.points(), sensor),
                io::PlyFormat::BinaryLittleEndian);
  io::write_ply(folder / (std::string(stem) + "_voxels.ply"), cloud_of(tree.voxelize(o.voxel), sensor),
                io::PlyFormat::BinaryLittleEndian);
}

/// Moving objects' trails when the frames carry labels: clearing on (the run's tree) against the
/// same configuration with clearing off (a second tree, run alongside for the comparison).
class TrailReport {
 public:
  explicit TrailReport(const Config& config) : meter_(config.box_side / 2) {
    if (config.clearing.enabled) {
      Config off = config;
      off.clearing.enabled = false;
      keeping_ = std::make_unique<EgoOctree>(off);
    }
  }

  /// Takes frame `t` in (the run's tree has taken it as `scan`); returns its trail (moving points held more
  /// than 5 frames after they were scanned).
  std::size_t frame(std::size_t t, const workloads::WorkloadFrame& frame, ScanView scan, const EgoOctree& tree) {
    meter_.add_scan(t, frame.world_T_sensor, frame.points, frame.labels);
    const std::vector<Eigen::Vector3d> held = tree.points();
    const bench::TrailMeter::Census on = meter_.census(held, t);
    const std::size_t trail = on.trail;
    trail_on_ += trail;
    if (keeping_) {
      const auto start = bench::Clock::now();
      keeping_->update(frame.world_T_sensor, scan);
      keeping_ms_ += bench::ms_since(start);
      const std::vector<Eigen::Vector3d> kept = keeping_->points();
      const bench::TrailMeter::Census off = meter_.census(kept, t);
      trail_off_ += off.trail;
      static_off_ += off.fixed;
      static_removed_ += meter_.static_missing(kept, held);
    }
    if (t % 10 == 9) meter_.forget_beyond(frame.world_T_sensor.translation());
    return trail;
  }

  /// `update_ms`: the run's tree's mean update time over `frames` frames.
  void print(double update_ms, std::size_t frames) const {
    std::printf("trail (moving-object points held > 5 frames after scanning, summed over frames): %zu\n", trail_on_);
    if (!keeping_) return;
    std::printf("with clearing off: trail %zu; clearing on keeps %.1f %% of it\n", trail_off_,
                trail_off_ ? 100.0 * double(trail_on_) / double(trail_off_) : 0.0);
    std::printf("static points held with clearing off but not on: %zu of %zu (%.3f %%, summed over frames)\n",
                static_removed_, static_off_, static_off_ ? 100.0 * double(static_removed_) / double(static_off_) : 0.0);
    const double off_ms = frames > 0 ? keeping_ms_ / double(frames) : 0.0;
    std::printf("mean update with clearing on / off: %.3f / %.3f ms = %.2fx\n", update_ms, off_ms,
                off_ms > 0 ? update_ms / off_ms : 0.0);
  }

 private:
  bench::TrailMeter meter_;
  std::unique_ptr<EgoOctree> keeping_;  // clearing off, for the comparison
  std::size_t trail_on_ = 0, trail_off_ = 0, static_off_ = 0, static_removed_ = 0;
  double keeping_ms_ = 0.0;
};

/// The options of a run keyed by `eco run`'s flags (without --out and --config).
nlohmann::json run_options_json(const RunOptions& o, const SourceFlags& source) {
  nlohmann::json out{{"frames", o.frames}, {"export-every", o.export_every}, {"voxel", o.voxel}, {"seed", o.seed},
                     {"save-every", o.save_every}};
  // paths resolved, so that --config works from anywhere
  source.add_to(out);
  if (!o.save.empty()) out["save"] = std::filesystem::weakly_canonical(o.save).string();
  if (!o.load.empty()) out["load"] = std::filesystem::weakly_canonical(o.load).string();
  return out;
}

/// The frames of --data, which must carry poses: ECO places each scan by its pose.
std::unique_ptr<workloads::Workload> posed_frames(const SourceFlags& source) {
  workloads::OpenedSource opened = source.open();
  std::printf("%s\n", opened.description.c_str());
  if (!opened.has_poses) {
    std::string topics;
    for (const std::string& t : opened.pose_topics) topics += (topics.empty() ? "" : ", ") + t;
    throw std::invalid_argument(source.data + " has no poses, and eco run places each scan by its pose: give --poses FILE "
                                "(KITTI or TUM)" + (topics.empty() ? "" : ", --pose-topic (it has " + topics + ")") +
                                ", or let eco odometry --data " + source.data + " estimate them");
  }
  return std::move(opened.frames);
}

int run(const RunOptions& o, const SourceFlags& source, const ViewFlags& viewing, const std::string& command_line) {
  std::unique_ptr<workloads::Workload> scans;
  const std::string& data = source.data;
  if (data.empty()) {
    sim::SimConfig sim;
    sim.seed = o.seed;
    sim.frames = source.options.start + (o.frames > 0 ? o.frames : 100);
    scans = source.from_start(std::make_unique<bench::SimWorkload>(sim));
  } else {
    scans = posed_frames(source);
  }
  // a loaded map goes on from the frame after its last, under its own configuration
  EgoOctree tree = o.load.empty() ? EgoOctree(o.config) : EgoOctree::load(o.load);
  const Config& config = tree.config();
  // a loaded map brings its own configuration: the file names the map, not the fields
  write_options_file(o.out, "run", command_line, run_options_json(o, source), o.load.empty() ? &config : nullptr);
  const std::size_t total = o.frames > 0 ? std::min(o.frames, scans->size()) : scans->size();
  const std::size_t first = tree.frame_count();
  std::printf("%s, %zu frames; %s\n", data.empty() ? "simulated drive" : data.c_str(), total,
              describe_settings(config).c_str());
  if (!o.load.empty()) std::printf("loaded %s: %zu points after frame %zu\n", o.load.c_str(), tree.size(), first - 1);
  std::printf("%6s %8s %8s %8s %8s %9s %8s %6s %6s %9s %7s\n", "frame", "scan", "inserted", "pruned", "cleared",
              "held", "nodes", "depth", "B/pt", "update ms", "trail");
  view::RunInfo shown{data.empty() ? "simulated drive" : data, config.box_side, o.voxel, total};
  shown.region = config.region.shape;
  shown.turn_with = config.region.turn_with;
  LiveView live(viewing, o.out, (std::filesystem::path(o.out) / "view").string(), shown);
  if (live.recorder() && first > 0) live.recorder()->carry(std::uint32_t(first - 1), tree.points_with_attributes());
  std::unique_ptr<TrailReport> trails;
  double update_ms = 0.0, read_ms = 0.0;
  for (std::size_t t = first; t < total; ++t) {
    const auto reading = bench::Clock::now();
    const workloads::WorkloadFrame frame = scans->frame(t);
    read_ms += bench::ms_since(reading);
    std::optional<workloads::AttributedScan> attributed;
    const ScanView scan = workloads::scan_for(frame, config.attributes, attributed);
    const auto start = bench::Clock::now();
    const UpdateStats u = tree.update(frame.world_T_sensor, scan);
    const double ms = bench::ms_since(start);
    update_ms += ms;
    if (!frame.labels.empty() && !trails) trails = std::make_unique<TrailReport>(config);
    const std::string trail = trails ? std::to_string(trails->frame(t, frame, scan, tree)) : "-";
    const Stats s = tree.stats();
    std::printf("%6zu %8zu %8zu %8zu %8zu %9zu %8zu %6.2f %6.1f %9.3f %7s\n", t, u.scan_points, u.inserted, u.pruned,
                u.cleared, s.points, s.nodes, s.mean_leaf_depth, s.points ? double(s.bytes) / double(s.points) : 0.0,
                ms, trail.c_str());
    if (o.export_every > 0 && (t % o.export_every == 0 || t + 1 == total)) export_frame(o, tree, t);
    if (o.save_every > 0 && t % o.save_every == o.save_every - 1) tree.save(save_path(o));
    if (view::Recorder* recorder = live.recorder()) {
      recorder->record(std::uint32_t(t), frame.world_T_sensor, tree.points_with_attributes(), tree.voxel_keys(o.voxel),
                       {u.scan_points, u.inserted, u.pruned + u.over_budget, u.cleared, s.points, ms, u.region});
      live.pace();
    }
  }
  if (!o.save.empty() || o.save_every > 0) {
    tree.save(save_path(o));
    std::printf("saved the map after frame %u to %s\n", tree.frame_count() - 1, save_path(o).c_str());
  }
  if (o.export_every > 0) std::printf("wrote <frame>_points.ply and <frame>_voxels.ply (ego frame) to %s\n", o.out.c_str());
  const std::size_t ran = total > first ? total - first : 0;
  if (ran > 0) {
    std::printf("a frame: %.2f ms to read (and decode or simulate), %.2f ms to update (read / update = %.2f)\n",
                read_ms / double(ran), update_ms / double(ran), update_ms > 0 ? read_ms / update_ms : 0.0);
  }
  if (trails) trails->print(ran ? update_ms / double(ran) : 0.0, ran);
  const std::string broken = tree.check_invariants();
  std::printf("invariants: %s\n", broken.empty() ? "all hold" : broken.c_str());
  if (live.recorder()) std::printf("recorded for eco view: %s/view\n", o.out.c_str());
  std::fflush(stdout);
  live.linger();
  return broken.empty() ? 0 : 1;
}

}  // namespace

Run add_run(CLI::App& app, const std::string& command_line) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Stream a sequence's scans through ECO, printing per-frame figures");
  auto source = std::make_shared<SourceFlags>(*cmd, "a simulated drive");
  cmd->add_option("--frames", o->frames, "frames to run (0 = all; 100 for the simulator)")->capture_default_str();
  cmd->add_option(both_spellings("--export-every"), o->export_every, "write held points and voxel map as PLY every K frames (0 = never)")
      ->capture_default_str();
  cmd->add_option("--out", o->out, "folder for config.json and the PLY files")->capture_default_str();
  cmd->add_option("--voxel", o->voxel, "voxel map resolution [m]")->capture_default_str();
  cmd->add_option("--seed", o->seed, "the simulator's seed without --data")->capture_default_str();
  cmd->add_option("--save", o->save, "write the map to FILE after the last frame (EgoOctree::save)");
  cmd->add_option(both_spellings("--save-every"), o->save_every, "also write it every K frames (to --save, else <out>/map.eco)")
      ->capture_default_str();
  cmd->add_option("--load", o->load, "go on from the map saved in FILE: its configuration, from the frame after its last")
      ->check(CLI::ExistingFile);
  auto viewing = std::make_shared<ViewFlags>(*cmd);
  auto flags = std::make_shared<ConfigFlags>(*cmd, o->config);
  auto file = std::make_shared<OptionsFile>(*cmd, "run");
  cmd->footer(
      "Defaults are the library's (raw scans: AllInBox, every point in the box, no density cap); the settings\n"
      "are printed first. --density_cap.cell_size 0.1 --density_cap.max_points 2 keeps 2 points per 10 cm cell.\n"
      "With labels (SemanticKITTI, as the simulator and kitti_mini_08 have), the run counts moving objects'\n"
      "trails; with --clearing.enabled true it also runs the same map without clearing and compares.\n"
      "The output folder gets config.json (feed it back with --config to repeat the run).\n"
      "Examples:\n"
      "  eco run --frames 50\n"
      "  eco run --data ../shared/data/kitti_mini_00 --export-every 5 --out results/run00\n"
      "  eco run --data ../shared/data/kitti_mini_00 --density_cap.cell_size 0.1 --density_cap.max_points 2\n"
      "  eco run --frames 60 --clearing.enabled true     the simulator's cars: their trails, cleared or kept\n"
      "  eco run --frames 50 --save results/run/map.eco && eco run --frames 100 --load results/run/map.eco\n"
      "                                                  the same drive in two runs: frames 0-49, then 50-99\n"
      "  eco run --frames 60 --view                        watch it in a browser as it runs (eco view: afterwards)");
  return [o, source, flags, file, viewing, command_line] {
    file->load();
    if (!o->load.empty() && !flags->given().empty()) {
      throw std::invalid_argument("--load goes on under the saved map's own configuration; drop " + flags->given());
    }
    flags->apply(o->config);
    return run(*o, *source, *viewing, command_line);
  };
}

}  // namespace eco::cli
