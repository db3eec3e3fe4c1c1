// Links against an installed ECO and checks one update, one query, and one frame from each
// dataset library.
#include <eco/eco.hpp>
#include <eco/io/pcd.hpp>
#include <eco/sim/simulator.hpp>
#include <eco/workloads/static_map.hpp>

#include <cstdio>

int main() {
  eco::EgoOctree tree;
  const std::vector<Eigen::Vector3f> scan = {{1.f, 2.f, 0.5f}, {-3.f, 0.f, 1.f}};
  tree.update(Eigen::Isometry3d::Identity(), scan);
  const auto nearest = tree.knn(Eigen::Vector3d(1.0, 2.0, 0.0), 1);
  bool ok = tree.size() == 2 && nearest.size() == 1 && nearest[0].sq_dist == 0.25;

  eco::sim::SimConfig config;
  config.frames = 1;
  config.lidar.columns = 100;
  const eco::io::PointCloud cloud = eco::sim::Simulator(config).frame(0).cloud;
  const auto compressed = eco::io::format_pcd(cloud, eco::io::PcdFormat::BinaryCompressed);
  ok = ok && cloud.size() > 1000 && eco::io::parse_pcd(compressed, "memory").points == cloud.points;
  const eco::workloads::StaticMap map({Eigen::Vector3d(1, 2, 3)});
  ok = ok && map.size() == 1;
  std::printf("eco %s consumer: %s\n", eco::kVersion, ok ? "ok" : "WRONG");
  return ok ? 0 : 1;
}
