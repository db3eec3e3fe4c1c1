// Writes a simulated drive in KITTI's layout and measures how fast frames are made.
// Usage: eco_simulate <folder> [frames = 100] [seed = 1]

#include <eco/sim/simulator.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s <folder> [frames = 100] [seed = 1]\n", argv[0]);
    return 2;
  }
  try {
    eco::sim::SimConfig config;
    if (argc > 2) config.frames = std::stoul(argv[2]);
    if (argc > 3) config.seed = std::stoull(argv[3]);
    const auto start = std::chrono::steady_clock::now();
    const eco::sim::Simulator sim(config);
    const auto built = std::chrono::steady_clock::now();
    std::size_t points = 0;
    for (std::size_t i = 0; i < sim.size(); ++i) points += sim.frame(i).cloud.size();
    const auto scanned = std::chrono::steady_clock::now();
    sim.write_kitti(argv[1]);
    const auto written = std::chrono::steady_clock::now();
    const auto seconds = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
    const double n = static_cast<double>(sim.size());
    std::printf("city: %zu static solids, built in %.2f s\n", sim.static_shape_count(), seconds(start, built));
    std::printf("scans: %zu frames, %.0f returns per frame\n", sim.size(), static_cast<double>(points) / n);
    std::printf("rate: %.1f frames/s simulated, %.1f frames/s simulated and written (a real sensor: %.0f)\n",
                n / seconds(built, scanned), n / seconds(scanned, written), config.rate_hz);
    std::printf("wrote %s (velodyne/, labels/, poses.txt, calib.txt, times.txt)\n", argv[1]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "eco_simulate: %s\n", e.what());
    return 1;
  }
  return 0;
}
