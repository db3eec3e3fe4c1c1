// `eco`: an EgoOctree, queried in batches spread over MapSettings::threads, kept between batches.

#include "odometry/maps.hpp"

#include <eco/ego_octree.hpp>

namespace eco::odometry {
namespace {

class EcoMap final : public LocalMap {
 public:
  explicit EcoMap(const MapSettings& settings) : tree_(ego_config(settings)), threads_(settings.threads) {}

  [[nodiscard]] std::string name() const override { return "eco"; }
  void update(const Eigen::Isometry3d& world_T_sensor, ScanView scan) override { tree_.update(world_T_sensor, scan); }
  void knn(std::span<const Eigen::Vector3d> queries, std::size_t k, std::span<Neighbor> out,
           std::span<std::size_t> found) const override {
    tree_.knn(queries, k, out, found, threads_);  // the helpers stay between the iterations' batches
  }
  [[nodiscard]] std::size_t size() const override { return tree_.size(); }
  [[nodiscard]] std::vector<Eigen::Vector3d> points() const override { return tree_.points(); }

 private:
  EgoOctree tree_;
  mutable QueryThreads threads_;  // batches run one after another: a query is const, the pool is not
};

}  // namespace

std::unique_ptr<LocalMap> make_eco_map(const MapSettings& settings) { return std::make_unique<EcoMap>(settings); }

}  // namespace eco::odometry
