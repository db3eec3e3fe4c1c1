// `eco`, `eco_exact`, `eco_clearing`, `eco_ball` and `eco_box`: the EgoOctree itself, through its
// public API.

#include "baselines/makers.hpp"

#include <eco/ego_octree.hpp>

#include <utility>

namespace eco::baselines {
namespace {

class EcoMethod final : public Method {
 public:
  EcoMethod(std::string name, const Config& config) : name_(std::move(name)), tree_(config) {}

  [[nodiscard]] std::string name() const override { return name_; }
  void update(const Eigen::Isometry3d& world_T_sensor, ScanView scan) override {
    tree_.update(world_T_sensor, scan);
  }
  std::size_t knn(const Eigen::Vector3d& query, std::span<Neighbor> out) const override {
    return tree_.knn(query, out);
  }
  using Method::knn;
  [[nodiscard]] std::vector<Neighbor> radius(const Eigen::Vector3d& query, double r) const override {
    return tree_.radius(query, r);
  }
  [[nodiscard]] std::vector<Eigen::Vector3d> box(const Eigen::Vector3d& lo,
                                                 const Eigen::Vector3d& hi) const override {
    return tree_.box(lo, hi);
  }
  [[nodiscard]] std::vector<VoxelKey> voxel_keys(double resolution) const override {
    return tree_.voxel_keys(resolution);
  }
  [[nodiscard]] std::vector<Eigen::Vector3d> points() const override { return tree_.points(); }
  [[nodiscard]] std::size_t size() const override { return tree_.size(); }
  [[nodiscard]] Stats stats() const override { return tree_.stats(); }
  [[nodiscard]] Eigen::Vector3d precision_origin() const override { return tree_.precision_origin(); }
  [[nodiscard]] std::string check_invariants() const override { return tree_.check_invariants(); }
  [[nodiscard]] const Config& config() const override { return tree_.config(); }
  [[nodiscard]] const Eigen::Isometry3d& pose() const override { return tree_.pose(); }
  [[nodiscard]] const EgoOctree* ego_octree() const override { return &tree_; }

 private:
  std::string name_;
  EgoOctree tree_;
};

}  // namespace

std::unique_ptr<Method> make_eco(const Config& config, Recentring recentring) {
  Config c = config;
  c.recentring = recentring;
  return std::make_unique<EcoMethod>(recentring == Recentring::Quantised ? "eco" : "eco_exact", c);
}

std::unique_ptr<Method> make_eco_ball(const Config& config) {
  Config c = config;
  if (c.region.shape != RegionShape::Ball) c.region = {RegionShape::Ball, c.box_side / 2};  // the most the cube holds
  return std::make_unique<EcoMethod>("eco_ball", c);
}

std::unique_ptr<Method> make_eco_box(const Config& config) {
  Config c = config;
  if (c.region.shape != RegionShape::OrientedBox) {  // a car's, mostly ahead: its corners stay within box_side / 2 as it turns
    const double l = c.box_side;
    c.region = {RegionShape::OrientedBox, 0.0, 0.39 * l, 0.2 * l, 0.3 * l, 0.3 * l, 0.25 * l, 0.25 * l};
  }
  return std::make_unique<EcoMethod>("eco_box", c);
}

std::unique_ptr<Method> make_eco_clearing(const Config& config) {
  Config c = config;
  c.clearing.enabled = true;
  return std::make_unique<EcoMethod>("eco_clearing", c);
}

}  // namespace eco::baselines
