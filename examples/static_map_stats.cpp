// The static workload's map for a KITTI-layout sequence at one or more voxel resolutions: map
// size and the points each box of side L holds along the drive.
// Usage: eco_static_map_stats <folder> <resolution> [more resolutions ...] [--box L]

#include <eco/workloads/dynamic_workload.hpp>
#include <eco/workloads/static_map.hpp>
#include <eco/workloads/static_workload.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s <folder> <resolution> [more resolutions ...] [--box L]\n", argv[0]);
    return 2;
  }
  try {
    double box = 20.0;
    std::vector<double> resolutions;
    for (int i = 2; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg == "--box" && i + 1 < argc) box = std::stod(argv[++i]);
      else resolutions.push_back(std::stod(arg));
    }
    const eco::workloads::DynamicWorkload scans{eco::io::KittiSequence(argv[1])};
    std::printf("%s: %zu scans, box %.1f m\n", argv[1], scans.size(), box);
    std::printf("%10s %12s %12s %12s %12s %12s\n", "resolution", "map points", "box mean", "box min",
                "box max", "ms/frame");
    for (const double r : resolutions) {
      const auto map = std::make_shared<const eco::workloads::StaticMap>(
          eco::workloads::StaticMap::aggregate(scans, r));
      const eco::workloads::StaticWorkload workload(map, scans.sequence().poses(), box);
      std::size_t total = 0, least = SIZE_MAX, most = 0;
      const auto start = std::chrono::steady_clock::now();
      for (std::size_t i = 0; i < workload.size(); ++i) {
        const std::size_t n = workload.frame(i).points.size();
        total += n;
        least = std::min(least, n);
        most = std::max(most, n);
      }
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      std::printf("%10.3f %12zu %12.0f %12zu %12zu %12.2f\n", r, map->size(),
                  static_cast<double>(total) / static_cast<double>(workload.size()), least, most,
                  ms / static_cast<double>(workload.size()));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "eco_static_map_stats: %s\n", e.what());
    return 1;
  }
  return 0;
}
