// make demo: streams the simulator's city (eco::sim) through ECO, both re-centring modes side
// by side, and prints per-frame figures. Usage: eco_demo [frames]

#include <eco/eco.hpp>
#include <eco/sim/simulator.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>

namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::atoi(argv[1]) : 60;
  eco::Config config;  // L = 20 m, quantised re-centring
  config.insert_policy = eco::InsertPolicy::AllInBox;  // raw scans ...
  config.density_cap = {0.1, 2};                        // ... kept to 2 points per 10 cm cell
  eco::Config exact = config;
  exact.recentring = eco::Recentring::Exact;
  eco::EgoOctree tree(config), paper(exact);
  eco::sim::SimConfig city;
  city.frames = static_cast<std::size_t>(std::max(frames, 1));
  const eco::sim::Simulator scene(city);
  std::mt19937 rng(7);

  std::printf("ECO %s demo: a simulated city drive (HDL-64E-like, seed %llu), %d frames, L = %.0f m, N_max = %u\n",
              eco::kVersion, static_cast<unsigned long long>(city.seed), frames, config.box_side,
              config.leaf_capacity);
  std::printf("%5s %8s %8s %7s %8s %8s %7s %6s %9s %9s %9s\n", "frame", "scan", "inserted", "pruned",
              "held", "nodes", "depth", "B/pt", "eco ms", "exact ms", "knn us");
  double eco_total = 0.0, exact_total = 0.0;
  for (int t = 0; t < frames; ++t) {
    const eco::sim::SimFrame frame = scene.frame(static_cast<std::size_t>(t));
    const Eigen::Isometry3d& pose = frame.world_T_lidar;
    const eco::ScanView scan = frame.cloud.view();
    auto start = std::chrono::steady_clock::now();
    const eco::UpdateStats st = tree.update(pose, scan);
    const double eco_ms = ms_since(start);
    start = std::chrono::steady_clock::now();
    paper.update(pose, scan);
    const double exact_ms = ms_since(start);
    if (t > 0) {  // the first frame builds from nothing in both modes
      eco_total += eco_ms;
      exact_total += exact_ms;
    }
    std::uniform_real_distribution<double> u(-8.0, 8.0);
    start = std::chrono::steady_clock::now();
    for (int i = 0; i < 100; ++i) {
      (void)tree.knn(pose.translation() + Eigen::Vector3d(u(rng), u(rng), u(rng) / 4), 5);
    }
    const double knn_us = ms_since(start) * 1000.0 / 100.0;
    const eco::Stats s = tree.stats();
    std::printf("%5d %8zu %8zu %7zu %8zu %8zu %7.2f %6.1f %9.3f %9.3f %9.2f\n", t, st.scan_points,
                st.inserted, st.pruned, s.points, s.nodes, s.mean_leaf_depth,
                double(s.bytes) / double(std::max<std::size_t>(s.points, 1)), eco_ms, exact_ms, knn_us);
  }
  if (frames > 1) {
    std::printf("\nmean update after the first frame: quantised %.3f ms, exact (paper) %.3f ms, ratio %.2fx\n",
                eco_total / (frames - 1), exact_total / (frames - 1), exact_total / eco_total);
  }
  const std::string broken = tree.check_invariants();
  std::printf("invariants: %s\n", broken.empty() ? "all hold" : broken.c_str());
  return broken.empty() ? 0 : 1;
}
