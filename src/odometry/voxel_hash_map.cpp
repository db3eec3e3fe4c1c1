// `voxel_hash`: the map KISS-ICP keeps (Vizzo et al. 2023), written here from its description. A
// hash map from voxel to at most N points (the first to arrive); a query looks only in the 27
// voxels around its own, so a nearer point two voxels away is missed: approximate by design.
// Voxels whose first point left the cube around the sensor are dropped whole.

#include "odometry/maps.hpp"
#include "odometry/voxel_downsample.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace eco::odometry {
namespace {

class VoxelHashMap final : public LocalMap {
 public:
  explicit VoxelHashMap(const MapSettings& settings)
      : side_(settings.cell_size), half_box_(settings.box_side / 2.0), max_points_(settings.max_points) {}

  [[nodiscard]] std::string name() const override { return "voxel_hash"; }
  [[nodiscard]] bool exact() const override { return false; }

  void update(const Eigen::Isometry3d& world_T_sensor, ScanView scan) override {
    const Eigen::Vector3d centre = world_T_sensor.translation();
    const auto inside = [&](const Eigen::Vector3d& p) { return (p - centre).cwiseAbs().maxCoeff() < half_box_; };
    std::erase_if(voxels_, [&](const auto& entry) {
      if (inside(entry.second.front())) return false;
      size_ -= entry.second.size();
      return true;
    });
    for (std::size_t i = 0; i < scan.count; ++i) {
      const Eigen::Vector3d p = world_T_sensor * scan[i].cast<double>();
      if (!inside(p)) continue;
      std::vector<Eigen::Vector3d>& voxel = voxels_[voxel_of(p, side_)];
      if (voxel.size() >= max_points_) continue;
      if (voxel.empty()) voxel.reserve(max_points_);
      voxel.push_back(p);
      ++size_;
    }
  }

  void knn(std::span<const Eigen::Vector3d> queries, std::size_t k, std::span<Neighbor> out,
           std::span<std::size_t> found) const override {
    for (std::size_t i = 0; i < queries.size(); ++i) found[i] = nearest(queries[i], out.subspan(i * k, k));
  }

  [[nodiscard]] std::size_t size() const override { return size_; }
  [[nodiscard]] std::vector<Eigen::Vector3d> points() const override {
    std::vector<Eigen::Vector3d> all;
    all.reserve(size_);
    for (const auto& [key, voxel] : voxels_) all.insert(all.end(), voxel.begin(), voxel.end());
    return all;
  }

 private:
  /// The nearest points in the 27 voxels around `query`'s, nearest first, into `out`.
  std::size_t nearest(const Eigen::Vector3d& query, std::span<Neighbor> out) const {
    candidates_.clear();
    const VoxelKey at = voxel_of(query, side_);
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto voxel = voxels_.find({at.x + dx, at.y + dy, at.z + dz});
          if (voxel == voxels_.end()) continue;
          for (const Eigen::Vector3d& p : voxel->second) candidates_.push_back({p, (p - query).squaredNorm(), {}});
        }
      }
    }
    const std::size_t n = std::min(out.size(), candidates_.size());
    const auto nearer = [](const Neighbor& a, const Neighbor& b) { return a.sq_dist < b.sq_dist; };
    std::partial_sort(candidates_.begin(), candidates_.begin() + std::ptrdiff_t(n), candidates_.end(), nearer);
    std::copy_n(candidates_.begin(), n, out.begin());
    return n;
  }

  double side_;
  double half_box_;
  std::size_t max_points_;
  std::unordered_map<VoxelKey, std::vector<Eigen::Vector3d>> voxels_;
  std::size_t size_ = 0;
  mutable std::vector<Neighbor> candidates_;  // one query's, kept warm (queries run on one thread)
};

}  // namespace

std::unique_ptr<LocalMap> make_voxel_hash_map(const MapSettings& settings) {
  return std::make_unique<VoxelHashMap>(settings);
}

}  // namespace eco::odometry
