// Links against an installed ECO and checks one update and one query.
#include <eco/eco.hpp>

#include <cstdio>

int main() {
  eco::EgoOctree tree;
  const std::vector<Eigen::Vector3f> scan = {{1.f, 2.f, 0.5f}, {-3.f, 0.f, 1.f}};
  tree.update(Eigen::Isometry3d::Identity(), scan);
  const auto nearest = tree.knn(Eigen::Vector3d(1.0, 2.0, 0.0), 1);
  const bool ok = tree.size() == 2 && nearest.size() == 1 && nearest[0].sq_dist == 0.25;
  std::printf("eco %s consumer: %s\n", eco::kVersion, ok ? "ok" : "WRONG");
  return ok ? 0 : 1;
}
