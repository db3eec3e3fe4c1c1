// `eco` and `eco_ball`: an EgoOctree (holding the cube, or a ball in it), queried in batches
// spread over MapSettings::threads, kept between batches.

#include "odometry/maps.hpp"

#include <eco/ego_octree.hpp>

namespace eco::odometry {
namespace {

class EcoMap final : public LocalMap {
 public:
  EcoMap(const MapSettings& settings, bool ball)
      : name_(ball ? "eco_ball" : "eco"), tree_(ego_config(settings, ball)), threads_(settings.threads) {}

  [[nodiscard]] std::string name() const override { return name_; }
  void update(const Eigen::Isometry3d& world_T_sensor, ScanView scan) override { tree_.update(world_T_sensor, scan); }
  void knn(std::span<const Eigen::Vector3d> queries, std::size_t k, std::span<Neighbor> out,
           std::span<std::size_t> found) const override {
    tree_.knn(queries, k, out, found, threads_);  // the helpers stay between the iterations' batches
  }
  [[nodiscard]] std::size_t size() const override { return tree_.size(); }
  [[nodiscard]] std::vector<Eigen::Vector3d> points() const override { return tree_.points(); }

 private:
  std::string name_;
  EgoOctree tree_;
  mutable QueryThreads threads_;  // batches run one after another: a query is const, the pool is not
};

}  // namespace

std::unique_ptr<LocalMap> make_eco_map(const MapSettings& settings, bool ball) {
  return std::make_unique<EcoMap>(settings, ball);
}

}  // namespace eco::odometry
