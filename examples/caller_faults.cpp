// What a map costs the code around it in page faults. A caller's own per-frame work runs between
// the map's updates and its page faults and time are counted: beside ECO, beside a heap-resident
// voxel-hash map (KISS-ICP's kind of map, odometry's `voxel_hash`), and with no map at all, each in
// a process of its own (the C library's heap remembers what a run did); each as the process
// starts and after eco::keep_freed_heap() (include/eco/process_heap.hpp).
//
//   eco_caller_faults DATA_DIR [CALLER [FRAMES [CELL_SIZE MAX_POINTS]]]
//
// DATA_DIR is a KITTI-layout folder (`eco simulate` writes one). CALLER is `preprocessing` (the
// default: a few scan-sized vectors a frame from two threads, as KISS-ICP's preprocessing
// allocates; src/bench/preprocessing_caller.hpp) or `bench` (the work `eco bench` times beside
// every update; src/bench/caller_work.hpp). Both maps hold the 200 m cube about the sensor, at
// most MAX_POINTS (default 20) per CELL_SIZE (default 1 m) cell: KISS-ICP's defaults. Prints each
// run's caller time and page faults a frame and the ratios of ECO's to the voxel-hash map's.

#include "bench/caller_work.hpp"
#include "bench/fork_alone.hpp"
#include "bench/preprocessing_caller.hpp"

#include <eco/io/kitti_sequence.hpp>
#include <eco/process_heap.hpp>
#include <eco/odometry/local_map.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

struct Run {
  double caller_ms = 0.0;
  double caller_faults = 0.0;  // a frame
};

struct Frames {
  std::vector<std::vector<Eigen::Vector3f>> scans;
  std::vector<Eigen::Isometry3d> poses;
};

/// The caller beside `map` (none: alone) over every frame, the first left out (it builds everything).
Run run(const Frames& frames, const std::string& caller_kind, eco::odometry::LocalMap* map) {
  std::optional<eco::bench::PreprocessingCaller> preprocessing;
  if (caller_kind == "preprocessing") preprocessing.emplace();
  Run total;
  double kept = 0.0;  // what the caller computed, so that it is not optimised away
  for (std::size_t t = 0; t < frames.scans.size(); ++t) {
    const eco::ScanView scan(frames.scans[t]);
    const eco::bench::CallerWork work = preprocessing ? preprocessing->run(scan) : eco::bench::run_caller_work(scan);
    kept += work.sum;
    if (map != nullptr) map->update(frames.poses[t], scan);
    if (t == 0) continue;
    total.caller_ms += work.ms;
    total.caller_faults += double(work.faults);
  }
  const double n = double(frames.scans.size() - 1);
  total.caller_ms /= n;
  total.caller_faults /= n;
  if (kept == 0.123456789) std::printf(" ");
  return total;
}

/// The first `count` frames of `sequence`.
Frames read_frames(const eco::io::KittiSequence& sequence, std::size_t count) {
  Frames frames;
  for (std::size_t t = 0; t < count; ++t) {
    const eco::io::KittiFrame frame = sequence.read(t);
    frames.scans.push_back(frame.cloud.points);
    frames.poses.push_back(frame.world_T_lidar);
  }
  return frames;
}

/// run() in a child process that reads the frames itself (memory the parent wrote would fault in
/// the child when written again); its figures come back through a pipe.
Run run_alone(const eco::io::KittiSequence& sequence, std::size_t count, const std::string& caller_kind, const std::string& map_name,
              const eco::odometry::MapSettings& settings, bool keep_freed_heap) {
  int ends[2];
  if (pipe(ends) != 0) throw std::runtime_error("pipe failed");
  const pid_t child = eco::bench::fork_alone();
  if (child == 0) {
    close(ends[0]);
    int status = 0;
    try {
      if (keep_freed_heap && !eco::keep_freed_heap()) throw std::runtime_error("eco::keep_freed_heap() refused");
      const Frames frames = read_frames(sequence, count);
      std::unique_ptr<eco::odometry::LocalMap> map;
      if (map_name != "alone") map = eco::odometry::make_local_map(map_name, settings);
      const Run result = run(frames, caller_kind, map.get());
      if (write(ends[1], &result, sizeof result) != ssize_t(sizeof result)) status = 1;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "eco_caller_faults (%s): %s\n", map_name.c_str(), e.what());
      status = 1;
    }
    _exit(status);
  }
  close(ends[1]);
  Run result;
  const bool read_all = read(ends[0], &result, sizeof result) == ssize_t(sizeof result);
  close(ends[0]);
  int status = 0;
  waitpid(child, &status, 0);
  if (!read_all || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("the run beside " + map_name + " failed");
  return result;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s DATA_DIR [preprocessing|bench [FRAMES [CELL_SIZE MAX_POINTS]]]\n", argv[0]);
    return 2;
  }
  try {
    const eco::io::KittiSequence sequence(argv[1]);
    const std::string caller_kind = argc > 2 ? argv[2] : "preprocessing";
    if (caller_kind != "preprocessing" && caller_kind != "bench")
      throw std::invalid_argument("the caller is '" + caller_kind + "', not preprocessing or bench");
    const std::size_t count = std::min<std::size_t>(sequence.size(), argc > 3 ? std::stoul(argv[3]) : 60);
    if (count < 2) throw std::invalid_argument("the folder holds fewer than 2 frames");
    eco::odometry::MapSettings settings;
    if (argc > 5) {
      settings.cell_size = std::stod(argv[4]);
      settings.max_points = std::uint32_t(std::stoul(argv[5]));
    }
    settings.validate();
    std::printf("caller: %s, %zu frames, cells %g m x %u\n", caller_kind.c_str(), count, settings.cell_size,
                settings.max_points);
    std::printf("%-11s | %-34s | %s\n", "", "as the process starts", "after eco::keep_freed_heap()");
    double faults[2][2] = {};  // [keep_freed_heap][voxel_hash, eco]
    for (const std::string map : {"alone", "voxel_hash", "eco"}) {
      std::printf("%-11s", map.c_str());
      for (const bool keep : {false, true}) {
        const Run r = run_alone(sequence, count, caller_kind, map, settings, keep);
        std::printf(" | caller %7.2f ms, %8.1f faults", r.caller_ms, r.caller_faults);
        if (map != "alone") faults[keep][map == "eco"] = r.caller_faults;
      }
      std::printf("\n");
    }
    std::printf("page faults a frame beside eco / beside voxel_hash: %.2fx as the process starts, %.2fx after "
                "eco::keep_freed_heap()\n",
                faults[0][1] / std::max(faults[0][0], 1.0), faults[1][1] / std::max(faults[1][0], 1.0));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "eco_caller_faults: %s\n", e.what());
    return 1;
  }
  return 0;
}
