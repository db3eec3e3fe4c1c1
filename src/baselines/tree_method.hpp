#pragma once
// The octree baselines keep their points in the same detail::Tree as ECO (node layout, leaf
// blocks, insertion, splitting) and answer queries with the same code (src/query); only their
// update strategy differs. This base class provides everything but update().

#include "clearing/clearing.hpp"
#include "core/density/density_cells.hpp"
#include "core/tree/invariants.hpp"
#include "core/tree/tree.hpp"
#include "query/queries.hpp"

#include "baselines/method.hpp"

#include <memory>
#include <string>
#include <utility>

namespace eco::baselines {

class TreeMethod : public Method {
 public:
  TreeMethod(std::string name, const Config& config)
      : name_(std::move(name)),
        tree_(config),
        clearing_(config.clearing.enabled ? std::make_unique<detail::ClearingState>() : nullptr),
        density_(detail::density_cells_for(config)) {}

  [[nodiscard]] std::string name() const override { return name_; }
  std::size_t knn(const Eigen::Vector3d& query, std::span<Neighbor> out) const override {
    return detail::knn_query(tree_, query, out, Frame::World);
  }
  using Method::knn;
  [[nodiscard]] std::vector<Neighbor> radius(const Eigen::Vector3d& query, double r) const override {
    return detail::radius_query(tree_, query, r, Frame::World);
  }
  [[nodiscard]] std::vector<Eigen::Vector3d> box(const Eigen::Vector3d& lo,
                                                 const Eigen::Vector3d& hi) const override {
    return detail::box_query(tree_, Eigen::Isometry3d::Identity(), lo, hi, Frame::World);
  }
  [[nodiscard]] std::vector<VoxelKey> voxel_keys(double resolution) const override {
    return detail::voxel_keys_of(tree_, resolution);
  }
  [[nodiscard]] std::vector<Eigen::Vector3d> points() const override {
    std::vector<Eigen::Vector3d> out;
    out.reserve(size());
    detail::for_each_held(tree_, [&](const Eigen::Vector3d& p) { out.push_back(p); });
    return out;
  }
  [[nodiscard]] std::size_t size() const override {
    return tree_.size();
  }
  [[nodiscard]] Stats stats() const override {
    Stats s = detail::tree_stats(tree_);
    if (clearing_) s.bytes += clearing_->bytes();
    if (density_) s.bytes += density_->bytes();
    return s;
  }
  [[nodiscard]] Eigen::Vector3d precision_origin() const override { return tree_.motion().anchor; }
  [[nodiscard]] std::string check_invariants() const override { return detail::check_tree(tree_, holds_only_the_box()); }
  [[nodiscard]] const Config& config() const override { return tree_.config(); }
  [[nodiscard]] const Eigen::Isometry3d& pose() const override { return tree_.motion().pose; }

 protected:
  /// Whether every held point lies in the current ego box (the invariants check it).
  [[nodiscard]] virtual bool holds_only_the_box() const { return true; }
  std::string name_;
  detail::Tree tree_;
  std::unique_ptr<detail::ClearingState> clearing_;  // free-space clearing's, while Config::clearing is on
  std::unique_ptr<detail::DensityCells> density_;    // the density cap's counts, while it is on
};

}  // namespace eco::baselines
