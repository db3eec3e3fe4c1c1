#include "bench/report.hpp"

#include "bench/config_json.hpp"

#include "bench/machine.hpp"
#include "bench/svg_plot.hpp"

#include <eco/io/error.hpp>
#include <eco/version.hpp>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace eco::bench {
namespace {

using nlohmann::json;

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw io::Error(path.string(), "", "cannot write");
}

std::string fixed(double v, int digits) {
  if (std::isnan(v)) return "–";
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

/// JSON has no NaN: a figure that does not apply is null.
json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

std::string now_utc() {
  const std::time_t t = std::time(nullptr);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buffer;
}

std::string manoeuvre_name(sim::Manoeuvre m) {
  for (const auto& [name, value] : sim::manoeuvre_names()) {
    if (value == m) return name;
  }
  return "route";
}

}  // namespace

json bench_options_json(const BenchOptions& o) {
  json out = {{"workload", to_string(o.workload)},
              {"methods", o.methods},
              {"frames", o.frames},
              {"map-resolution", o.map_resolution},
              {"voxel", o.voxel_resolution},
              {"knn-queries", o.knn_queries},
              {"k", o.knn_k},
              {"seed", o.seed},
              {"sim-frames", o.sim_frames},
              {"sim-manoeuvre", manoeuvre_name(o.sim.manoeuvre)},
              {"sim-speed", o.sim.speed},
              {"sim-spin-rate", o.sim.spin_rate_deg},
              {"sim-roundabout-radius", o.sim.roundabout_radius},
              {"check", o.check_every_frame}};
  if (o.data) out["data"] = std::filesystem::weakly_canonical(*o.data).string();  // --config works from anywhere
  out.update(source_options_json(o.source));
  return out;
}

json source_options_json(const workloads::SourceOptions& o) {
  json out = json::object();
  if (o.start > 0) out["start"] = o.start;
  if (!o.poses.empty()) out["poses"] = std::filesystem::weakly_canonical(o.poses).string();
  if (!o.recording.topic.empty()) out["topic"] = o.recording.topic;
  if (!o.pose_topic.empty()) out["pose-topic"] = o.pose_topic;
  if (!o.fixed_frame.empty()) out["fixed-frame"] = o.fixed_frame;
  if (!o.recording.time.field.empty()) out["time-field"] = o.recording.time.field;
  if (o.recording.time.unit != io::TimeUnit::Auto) out["time-unit"] = io::name_of(o.recording.time.unit);
  return out;
}

namespace {

json run_json(const BenchRun& run, const std::string& command_line) {
  return {{"version", kVersion},
          {"command_line", command_line},
          {"date", now_utc()},
          {"machine", describe_machine()},
          {"bench", bench_options_json(run.options)},
          {"config", config_to_json(run.options.config)},
          {"result",
           {{"source", run.source},
            {"frames_run", run.methods.empty() ? 0 : run.methods.front().frames.size()},
            {"map_points", run.map_points},
            {"chamfer_reference", run.chamfer_reference},
            {"seconds", run.seconds},
            {"note", "eco_exact always runs with recentring = Exact; octree_base and the i-Octree baselines "
                     "place their roots themselves"}}}};
}

std::string csv(const MethodRun& m) {
  std::ostringstream s;
  s << "frame,input_points,update_ms,update_faults,caller_ms,caller_faults,voxel_ms,knn_ms,points,nodes,mean_depth,"
       "max_depth,bytes,chamfer_m,region_tested,region_scale,over_budget\n";
  s << std::setprecision(6);
  for (const FrameRecord& r : m.frames) {
    s << r.frame << ',' << r.input_points << ',' << r.update_ms << ',' << r.update_faults << ',' << r.caller_ms << ','
      << r.caller_faults << ',' << r.voxel_ms << ',' << r.knn_ms << ','
      << r.points << ',' << r.nodes << ',' << r.mean_depth << ',' << r.max_depth << ',' << r.bytes << ','
      << (std::isnan(r.chamfer_m) ? std::string() : fixed(r.chamfer_m, 6)) << ',' << r.region_tested << ','
      << r.region_scale << ',' << int(r.over_budget) << '\n';
  }
  return s.str();
}

json summary_json(const BenchRun& run, const std::vector<MethodSummary>& summaries) {
  json methods = json::object();
  for (const MethodSummary& s : summaries) {
    methods[s.name] = {{"frames", s.frames},
                       {"first_update_ms", s.first_update_ms},
                       {"update_ms", s.update_ms},
                       {"update_ms_p99", s.update_ms_p99},
                       {"update_faults", s.update_faults},
                       {"caller_ms", s.caller_ms},
                       {"caller_faults", s.caller_faults},
                       {"voxel_ms", s.voxel_ms},
                       {"knn_ms", s.knn_ms},
                       {"mean_depth", s.mean_depth},
                       {"first_frame_depth", s.first_depth},
                       {"last_frame_depth", s.last_depth},
                       {"max_depth", s.max_depth},
                       {"bytes", s.bytes},
                       {"bytes_per_point", s.bytes_per_point},
                       {"points", s.points},
                       {"nodes", s.nodes},
                       {"chamfer_m", number(s.chamfer_m)},
                       {"region_tested", s.region_tested},
                       {"region_scale_min", s.region_scale_min},
                       {"frames_over_budget", s.frames_over_budget}};
  }
  for (const MethodRun& m : run.methods) {
    if (!m.map_file) continue;
    const MapFileTiming& f = *m.map_file;
    methods[m.name].update({{"map_save_ms", f.save_ms},
                            {"map_load_ms", f.load_ms},
                            {"map_raw_ms", f.raw_ms},
                            {"map_file_bytes", f.file_bytes},
                            {"map_point_bytes", f.point_bytes}});
  }
  json out = {{"workload", to_string(run.options.workload)}, {"source", run.source}, {"methods", methods}};
  if (const auto& t = run.snapshots) {
    out["snapshots"] = {{"frames", t->frames},
                        {"update_alone_ms", t->update_alone_ms},
                        {"update_read_ms", t->update_read_ms},
                        {"update_beside_ms", t->update_beside_ms},
                        {"publish_ms", t->publish_ms},
                        {"knn_live_ms", t->knn_live_ms},
                        {"knn_snapshot_ms", t->knn_snapshot_ms},
                        {"bytes_alone", t->bytes_alone},
                        {"bytes_with_snapshot", t->bytes_with_snapshot},
                        {"reader_queries", t->reader_queries}};
  }
  return out;
}

const MethodSummary* find(const std::vector<MethodSummary>& summaries, const std::string& name) {
  for (const MethodSummary& s : summaries) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

}  // namespace

std::string summary_tables(const BenchRun& run, const std::vector<MethodSummary>& summaries) {
  const MethodSummary* eco = find(summaries, "eco");
  std::ostringstream s;
  s << "Table II shape (ms per frame, mean over the frames after the first; KNN = one batch of " << run.options.knn_queries << " queries, k = "
    << run.options.knn_k << "):\n\n| workload |";
  for (const MethodSummary& m : summaries) s << ' ' << m.name << " update | voxel | KNN |";
  s << "\n|---|";
  for (std::size_t i = 0; i < summaries.size(); ++i) s << "--:|--:|--:|";
  s << "\n| " << to_string(run.options.workload) << " |";
  for (const MethodSummary& m : summaries) {
    s << ' ' << fixed(m.update_ms, 2) << " | " << fixed(m.voxel_ms, 2) << " | " << fixed(m.knn_ms, 2) << " |";
  }
  const MethodSummary* pass = find(summaries, "scan_pass");
  auto ratio = [](const MethodSummary* a, double MethodSummary::*field, const MethodSummary* b) {
    return a && b ? fixed(a->*field / b->*field, 2) + "×" : std::string("–");
  };
  s << "\n\n| method | first update ms | update ms | p99 ms | p99 / mean | voxel ms | KNN ms | held points | nodes | "
       "leaf depth first → last | max depth | bytes/point | peak MB | Chamfer m | update / scan_pass | "
       "update / eco | voxel / eco | KNN / eco |\n"
    << "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const MethodSummary& m : summaries) {
    const bool octree = m.nodes > 0;
    s << "| " << m.name << " | " << fixed(m.first_update_ms, 1) << " | " << fixed(m.update_ms, 3) << " | "
      << fixed(m.update_ms_p99, 3) << " | " << fixed(m.update_ms_p99 / m.update_ms, 2) << " | " << fixed(m.voxel_ms, 3)
      << " | " << fixed(m.knn_ms, 3) << " | " << fixed(m.points, 0) << " | " << (octree ? fixed(m.nodes, 0) : "–")
      << " | " << (octree ? fixed(m.first_depth, 2) + " → " + fixed(m.last_depth, 2) : "–") << " | "
      << (octree ? std::to_string(m.max_depth) : "–") << " | " << fixed(m.bytes_per_point, 1) << " | "
      << fixed(double(m.bytes) / 1e6, 1) << " | " << fixed(m.chamfer_m, 4) << " | "
      << ratio(&m, &MethodSummary::update_ms, pass) << " | " << ratio(&m, &MethodSummary::update_ms, eco) << " | "
      << ratio(&m, &MethodSummary::voxel_ms, eco) << " | " << ratio(&m, &MethodSummary::knn_ms, eco) << " |\n";
  }
  const MethodSummary* pcl = find(summaries, "pcl_octree");
  const MethodSummary* kd = find(summaries, "nanoflann");
  const auto times_eco = [&](const MethodSummary* m, double MethodSummary::*field) {
    return (m ? m->name : std::string("–")) + " " + ratio(m, field, eco);
  };
  s << "\nECO against the others, each figure × ECO's time (goals: docs/benchmarks.md): update "
    << times_eco(pass, &MethodSummary::update_ms) << ", " << times_eco(pcl, &MethodSummary::update_ms) << ", "
    << times_eco(kd, &MethodSummary::update_ms) << "; voxel map " << times_eco(pcl, &MethodSummary::voxel_ms)
    << "; KNN " << times_eco(kd, &MethodSummary::knn_ms) << "; ECO's update p99 / mean "
    << (eco ? fixed(eco->update_ms_p99 / eco->update_ms, 2) + "×" : "–") << ".\n";
  s << "\nWhat each map costs its caller (per frame, after the first: page faults of the update, then the "
       "caller's own work right after it, a registration loop's preprocessing: a vector grown to the scan's size and a voxel hash map, allocated and freed):\n\n"
       "| method | update faults | caller ms | caller faults | caller / scan_pass's |\n|---|--:|--:|--:|--:|\n";
  for (const MethodSummary& m : summaries) {
    s << "| " << m.name << " | " << fixed(m.update_faults, 0) << " | " << fixed(m.caller_ms, 3) << " | "
      << fixed(m.caller_faults, 0) << " | " << ratio(&m, &MethodSummary::caller_ms, pass) << " |\n";
  }
  bool header = false;
  for (const MethodRun& m : run.methods) {
    if (!m.map_file) continue;
    const MapFileTiming& f = *m.map_file;
    if (!header) {
      s << "\nThe map file after the last frame (EgoOctree::save, flushed to the disk, then load; against writing, "
           "flushing and reading the same bytes raw; best of 3):\n\n"
           "| method | file MB | file / the points' coordinates and attributes | save ms | load ms | raw ms | "
           "(save + load) / raw |\n|---|--:|--:|--:|--:|--:|--:|\n";
      header = true;
    }
    s << "| " << m.name << " | " << fixed(double(f.file_bytes) / 1e6, 2) << " | "
      << (f.point_bytes ? fixed(double(f.file_bytes) / double(f.point_bytes), 2) + "×" : std::string("–")) << " | "
      << fixed(f.save_ms, 2) << " | " << fixed(f.load_ms, 2) << " | " << fixed(f.raw_ms, 2) << " | "
      << fixed((f.save_ms + f.load_ms) / f.raw_ms, 2) << "× |\n";
  }
  if (const auto& t = run.snapshots) {
    s << "\nSnapshots (a tree publishing one after every update and holding it a frame more, a reader thread "
         "querying the last one during the update; against a tree alone; means over "
      << t->frames << " frames):\n\n"
      << "| publish / update | KNN on the snapshot / on the tree | update, read meanwhile / alone | "
         "a tree that never publishes, updated beside the reader / alone | "
         "memory, one snapshot held / alone | reader's queries |\n|--:|--:|--:|--:|--:|--:|\n"
      << "| " << fixed(t->publish_ms / t->update_alone_ms, 3) << "× | " << fixed(t->knn_snapshot_ms / t->knn_live_ms, 2)
      << "× | " << fixed(t->update_read_ms / t->update_alone_ms, 2) << "× | "
      << fixed(t->update_beside_ms / t->update_alone_ms, 2) << "× | " << fixed(t->bytes_with_snapshot / t->bytes_alone, 2) << "× | " << t->reader_queries << " |\n";
  }
  if (const MethodSummary* clearing = find(summaries, "eco_clearing")) {
    s << "\nFree-space clearing: eco_clearing update / eco " << ratio(clearing, &MethodSummary::update_ms, eco)
      << ", Chamfer " << fixed(clearing->chamfer_m, 4) << " m against eco's " << (eco ? fixed(eco->chamfer_m, 4) : "–")
      << " m.\n";
  }
  return s.str();
}

std::string brief_table(const std::vector<MethodSummary>& summaries) {
  const MethodSummary* eco = find(summaries, "eco");
  // a time and its ratio to ECO's, or dashes where the method has no such figure (scan_pass)
  const auto cells = [&](const MethodSummary& m, double MethodSummary::*field, int width) {
    char text[64];
    const double v = m.*field;
    if (!std::isfinite(v)) {
      std::snprintf(text, sizeof text, "%*s | %8s", width, "-", "-");  // ASCII: printf pads bytes
    } else if (eco && eco->*field > 0) {
      std::snprintf(text, sizeof text, "%*.2f | %7.2f×", width, v, v / eco->*field);
    } else {
      std::snprintf(text, sizeof text, "%*.2f | %8s", width, v, "-");
    }
    return std::string(text);
  };
  std::ostringstream s;
  s << "ms per frame (mean after the first); × ECO's: the method's time over ECO's\n\n"
    << "| method         | update |  × ECO's | voxel map |  × ECO's |    KNN |  × ECO's |\n"
    << "|----------------|-------:|---------:|----------:|---------:|-------:|---------:|\n";
  for (const MethodSummary& m : summaries) {
    char name[32];
    std::snprintf(name, sizeof name, "| %-14s | ", m.name.c_str());
    s << name << cells(m, &MethodSummary::update_ms, 6) << " | " << cells(m, &MethodSummary::voxel_ms, 9) << " | "
      << cells(m, &MethodSummary::knn_ms, 6) << " |\n";
  }
  return s.str();
}

std::filesystem::path fresh_results_folder(const std::filesystem::path& given) {
  namespace fs = std::filesystem;
  if (!given.empty()) {
    for (const char* earlier : {"config.json", "summary.md"}) {
      if (fs::exists(given / earlier)) {
        throw io::Error(given.string(), "", std::string("holds an earlier run (") + earlier +
                                                "): each run goes into a folder of its own; give another --out, or "
                                                "remove this one");
      }
    }
    return given;
  }
  const std::time_t t = std::time(nullptr);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "bench-%Y%m%d-%H%M%S", std::gmtime(&t));
  fs::path folder = fs::path("results") / stamp;
  for (int n = 2; fs::exists(folder); ++n) folder = fs::path("results") / (std::string(stamp) + "-" + std::to_string(n));
  return folder;
}

void write_results(const std::filesystem::path& folder, const BenchRun& run, const std::string& command_line) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) throw io::Error(folder.string(), "", "cannot create the results folder: " + error.message());
  const std::vector<MethodSummary> summaries = summarize(run);
  write_file(folder / "config.json", run_json(run, command_line).dump(2) + "\n");
  for (const MethodRun& m : run.methods) write_file(folder / (m.name + ".csv"), csv(m));
  write_file(folder / "summary.json", summary_json(run, summaries).dump(2) + "\n");
  std::ostringstream md;
  md << "# ECO benchmark: " << to_string(run.options.workload) << " workload\n\n"
     << "- source: " << run.source << "\n- frames: " << (summaries.empty() ? 0 : summaries.front().frames)
     << (run.map_points ? ", static map of " + std::to_string(run.map_points) + " points" : std::string())
     << "\n- L = " << run.options.config.box_side << " m, N_max = " << run.options.config.leaf_capacity
     << ", insert policy " << (run.options.config.insert_policy == InsertPolicy::ShiftInOnly ? "ShiftInOnly" : "AllInBox")
     << ", voxel map at " << run.options.voxel_resolution << " m\n- machine: " << describe_machine()
     << "\n- version " << kVersion << ", command: `" << command_line << "`\n\n"
     << summary_tables(run, summaries)
     << "\nChamfer: each method's voxel map (clipped to the ego box) against " << run.chamfer_reference
     << "'s, mean of the two directed mean nearest-voxel distances"
     << (run.chamfer_reference == "scan_only"
             ? " (the paper's dynamic comparison: scan_only holds the current scan's in-box points alone, so the "
               "distance measures what a map remembers of earlier frames, moving objects' trails among it)"
             : "")
     << ". Depth and nodes: – for the k-d tree.\n";
  write_file(folder / "summary.md", md.str());
  write_update_plot(folder / "update_ms.svg", run);
}

}  // namespace eco::bench
