// What a map costs the code around it: a registration loop's own per-frame work (the one
// `eco bench` times beside every update, src/bench/caller_work.hpp: the scan copied into a vector
// grown as points come, one point kept per 1 m voxel through a hash map) runs between the map's
// updates, and its page faults and time are counted, with the map and without one, in a process
// of its own.
//
//   eco_caller_faults DATA_DIR [CELL_SIZE MAX_POINTS [FRAMES [alone|eco]]]
//
// DATA_DIR is a KITTI-layout folder (`eco simulate` writes one); the map is capped at MAX_POINTS
// per CELL_SIZE cell (default 0.5 m, 1). Runs the caller with the map (eco, the default) or
// without (alone): one per process, since the C library's heap remembers what a run did. Prints
// the caller's mean time and page faults per frame, and the update's.

#include "bench/caller_work.hpp"

#include <eco/eco.hpp>
#include <eco/io/kitti_sequence.hpp>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s DATA_DIR [CELL_SIZE MAX_POINTS [FRAMES [alone|eco]]]\n", argv[0]);
    return 2;
  }
  try {
    const eco::io::KittiSequence sequence(argv[1]);
    eco::Config config;
    config.density_cap = {argc > 2 ? std::stod(argv[2]) : 0.5, argc > 3 ? std::uint32_t(std::stoul(argv[3])) : 1u};
    const std::size_t frames = std::min<std::size_t>(sequence.size(), argc > 4 ? std::stoul(argv[4]) : 120);
    if (frames < 2) throw std::invalid_argument("the folder holds fewer than 2 frames");
    std::vector<std::vector<Eigen::Vector3f>> scans;
    std::vector<Eigen::Isometry3d> poses;
    for (std::size_t t = 0; t < frames; ++t) {
      const eco::io::KittiFrame frame = sequence.read(t);
      scans.push_back(frame.cloud.points);
      poses.push_back(frame.world_T_lidar);
    }
    const std::string mode = argc > 5 ? argv[5] : "eco";
    if (mode != "eco" && mode != "alone") throw std::invalid_argument("the mode is '" + mode + "', not alone or eco");
    const bool with_map = mode == "eco";
    eco::EgoOctree map(config);
    double caller_ms = 0.0, update_ms = 0.0;
    long caller_faults = 0, update_faults = 0;
    double kept = 0.0;  // what the caller computed, so that it is not optimised away
    for (std::size_t t = 0; t < frames; ++t) {
      const eco::bench::CallerWork caller = eco::bench::run_caller_work(eco::ScanView(scans[t]));
      kept += caller.sum;
      const long before = eco::bench::minor_faults();
      const auto start = std::chrono::steady_clock::now();
      if (with_map) map.update(poses[t], eco::ScanView(scans[t]));
      const double update = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      if (t == 0) continue;  // the first frame builds everything
      caller_ms += caller.ms;
      update_ms += update;
      caller_faults += caller.faults;
      update_faults += eco::bench::minor_faults() - before;
    }
    const double n = double(frames - 1);
    std::printf("%-8s caller %.2f ms, %.0f page faults a frame; update %.2f ms, %.0f page faults a frame (%g)\n",
                with_map ? "with ECO" : "alone", caller_ms / n, double(caller_faults) / n, update_ms / n,
                double(update_faults) / n, kept);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "eco_caller_faults: %s\n", e.what());
    return 1;
  }
  return 0;
}
