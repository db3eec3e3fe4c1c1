#include "bench/chamfer.hpp"

#include <nanoflann.hpp>

#include <cmath>
#include <limits>

namespace eco::bench {
namespace {

struct KeyCloud {
  const std::vector<VoxelKey>& keys;
  [[nodiscard]] std::size_t kdtree_get_point_count() const { return keys.size(); }
  [[nodiscard]] double kdtree_get_pt(std::size_t i, std::size_t axis) const {
    const VoxelKey& k = keys[i];
    return double(axis == 0 ? k.x : axis == 1 ? k.y : k.z);
  }
  template <class Bbox>
  bool kdtree_get_bbox(Bbox&) const {
    return false;
  }
};

using KeyTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, KeyCloud, double>,
                                                    KeyCloud, 3, std::uint32_t>;

/// Mean distance, in voxels, from each key of `from` to the nearest key of `to`.
double mean_nearest(const std::vector<VoxelKey>& from, const std::vector<VoxelKey>& to) {
  const KeyCloud cloud{to};
  const KeyTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  double sum = 0.0;
  for (const VoxelKey& k : from) {
    if (std::binary_search(to.begin(), to.end(), k)) continue;  // distance 0
    const double q[3] = {double(k.x), double(k.y), double(k.z)};
    std::uint32_t index = 0;
    double d2 = 0.0;
    tree.knnSearch(q, 1, &index, &d2);
    sum += std::sqrt(d2);
  }
  return sum / double(from.size());
}

}  // namespace

double chamfer_distance(const std::vector<VoxelKey>& a, const std::vector<VoxelKey>& b, double resolution) {
  if (a == b) return 0.0;
  if (a.empty() || b.empty()) return std::numeric_limits<double>::infinity();
  return resolution * (mean_nearest(a, b) + mean_nearest(b, a)) / 2.0;
}

std::vector<VoxelKey> clip_to_box(const std::vector<VoxelKey>& keys, const Eigen::Vector3d& lo,
                                  const Eigen::Vector3d& hi, double resolution) {
  // voxel i spans [i*res, (i+1)*res): it meets [lo, hi) when i*res < hi and (i+1)*res > lo
  std::vector<VoxelKey> out;
  for (const VoxelKey& k : keys) {
    const std::int64_t v[3] = {k.x, k.y, k.z};
    bool meets = true;
    for (int a = 0; a < 3; ++a) {
      meets = meets && double(v[a]) * resolution < hi[a] && double(v[a] + 1) * resolution > lo[a];
    }
    if (meets) out.push_back(k);
  }
  return out;
}

}  // namespace eco::bench
