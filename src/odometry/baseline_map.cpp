// `nanoflann` and `pcl_octree`: the benchmark's baselines (src/baselines/method.hpp) behind the
// odometry's interface. They hold exactly the points ECO holds (its admission and density cap)
// and answer exact KNN, one query at a time.

#include "odometry/baseline_maps.hpp"

#include "odometry/maps.hpp"

#include "baselines/method.hpp"

#include <algorithm>

namespace eco::odometry {
namespace {

class BaselineMap final : public LocalMap {
 public:
  BaselineMap(std::string_view name, const MapSettings& settings)
      : method_(baselines::make_method(name, ego_config(settings))) {}

  [[nodiscard]] std::string name() const override { return method_->name(); }
  void update(const Eigen::Isometry3d& world_T_sensor, ScanView scan) override { method_->update(world_T_sensor, scan); }
  void knn(std::span<const Eigen::Vector3d> queries, std::size_t k, std::span<Neighbor> out,
           std::span<std::size_t> found) const override {
    for (std::size_t i = 0; i < queries.size(); ++i) found[i] = method_->knn(queries[i], out.subspan(i * k, k));
  }
  [[nodiscard]] std::size_t size() const override { return method_->size(); }
  [[nodiscard]] std::vector<Eigen::Vector3d> points() const override { return method_->points(); }

 private:
  std::unique_ptr<baselines::Method> method_;
};

}  // namespace

const std::vector<std::string>& all_local_map_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all = local_map_names();
    all.insert(all.end(), {"nanoflann", "pcl_octree"});
    return all;
  }();
  return names;
}

std::unique_ptr<LocalMap> make_any_local_map(std::string_view name, const MapSettings& settings) {
  settings.validate();
  if (name == "nanoflann" || name == "pcl_octree") return std::make_unique<BaselineMap>(name, settings);
  if (std::ranges::find(local_map_names(), name) != local_map_names().end()) return make_local_map(name, settings);
  throw unknown_map(name, all_local_map_names());
}

}  // namespace eco::odometry
