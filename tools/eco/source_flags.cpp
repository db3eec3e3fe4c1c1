#include "source_flags.hpp"
#include "spellings.hpp"

#include "bench/report.hpp"

#include <eco/io/error.hpp>
#include <eco/workloads/frame_window.hpp>

#include <cstdio>
#include <filesystem>

namespace eco::cli {

SourceFlags::SourceFlags(CLI::App& cmd, const std::string& without_data) {
  cmd.add_option("--data", data,
                 "a KITTI-layout folder, a folder of .pcd/.ply/.bin files, an .mcap or .db3 file or a rosbag2 folder; "
                 "default: " + without_data);
  cmd.add_option("--poses", options.poses,
                 "poses from this file (KITTI: 12 numbers a line, a scan a line; TUM: t x y z qx qy qz qw, at the "
                 "clouds' stamps) instead of the data's own");
  cmd.add_option("--start", options.start, "the first frame taken (0: the first): the run begins there, on any source")
      ->capture_default_str();
  cmd.add_option("--topic", options.recording.topic, "the recording's PointCloud2 topic (default: the only one)");
  cmd.add_option(both_spellings("--pose-topic"), options.pose_topic,
                 "poses from the recording's nav_msgs/Odometry, geometry_msgs/PoseStamped or TransformStamped topic "
                 "(tf applied from its frame to the clouds'), or tf: the clouds' frame through /tf and /tf_static; "
                 "at each cloud's stamp, and at each point's time when points have times");
  cmd.add_option(both_spellings("--fixed-frame"), options.fixed_frame,
                 "with --pose-topic tf: the frame the clouds are placed in (default: the root of their tf tree)");
  cmd.add_option(both_spellings("--time-field"), options.recording.time.field,
                 "the point field holding each point's time (default: the first of t, time, timestamp, timestamps, "
                 "offset_time, stamps)");
  cmd.add_option(both_spellings("--time-unit"), time_unit, "its unit: s, ms, us, ns, or auto (integers ns, floats s)")
      ->check(CLI::IsMember({"auto", "s", "ms", "us", "ns"}))
      ->capture_default_str();
}

workloads::SourceOptions SourceFlags::resolved() const {
  workloads::SourceOptions read = options;
  read.recording.time.unit = *io::time_unit_named(time_unit);
  return read;
}

std::unique_ptr<workloads::Workload> SourceFlags::from_start(std::unique_ptr<workloads::Workload> frames) const {
  return workloads::frame_window(std::move(frames), options.start);
}

workloads::OpenedSource SourceFlags::open() const {
  workloads::OpenedSource source = workloads::open_source(data, resolved());
  for (const std::string& warning : source.warnings) std::fprintf(stderr, "eco: warning: %s\n", warning.c_str());
  return source;
}

void SourceFlags::add_to(nlohmann::json& out) const {
  if (!data.empty()) out["data"] = std::filesystem::weakly_canonical(data).string();
  out.update(bench::source_options_json(resolved()));
}

}  // namespace eco::cli
