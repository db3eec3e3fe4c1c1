#include <eco/workloads/static_map.hpp>

#include "workloads/grid_key.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace eco::workloads {

namespace {

struct Centroid {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::uint64_t count = 0;
};

std::uint64_t key_or_throw(const Eigen::Vector3d& p, double side, const char* what) {
  const auto key = detail::grid_key(p, side);
  if (!key) {
    throw std::invalid_argument(std::string("eco::workloads::StaticMap: ") + what + " of " +
                                std::to_string(side) + " m cannot index the point (" +
                                std::to_string(p.x()) + ", " + std::to_string(p.y()) + ", " +
                                std::to_string(p.z()) + "): over 2^20 cells from the origin");
  }
  return *key;
}

}  // namespace

StaticMap StaticMap::aggregate(const Workload& scans, double resolution) {
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw std::invalid_argument("eco::workloads::StaticMap: resolution = " + std::to_string(resolution) +
                                " must be positive and finite");
  }
  std::unordered_map<std::uint64_t, Centroid> voxels;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const WorkloadFrame frame = scans.frame(i);
    for (const Eigen::Vector3f& p : frame.points) {
      if (!p.allFinite()) continue;
      const Eigen::Vector3d world = frame.world_T_sensor * p.cast<double>();
      Centroid& c = voxels[key_or_throw(world, resolution, "a resolution")];
      c.sum += world;
      ++c.count;
    }
  }
  // Centroids in key order, so the map is the same whatever the hash table's order.
  std::vector<std::pair<std::uint64_t, Eigen::Vector3d>> keyed;
  keyed.reserve(voxels.size());
  for (const auto& [key, c] : voxels) keyed.emplace_back(key, c.sum / static_cast<double>(c.count));
  std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Eigen::Vector3d> points;
  points.reserve(keyed.size());
  for (const auto& entry : keyed) points.push_back(entry.second);
  return StaticMap(std::move(points));
}

StaticMap::StaticMap(std::vector<Eigen::Vector3d> points, double bucket) : bucket_(bucket) {
  if (!(bucket > 0.0) || !std::isfinite(bucket)) {
    throw std::invalid_argument("eco::workloads::StaticMap: bucket = " + std::to_string(bucket) +
                                " must be positive and finite");
  }
  // Sort the points by bucket so each bucket is one contiguous range.
  std::vector<std::uint64_t> keys(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) keys[i] = key_or_throw(points[i], bucket, "a bucket");
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });
  points_.reserve(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::uint64_t key = keys[order[i]];
    if (i == 0 || key != keys[order[i - 1]]) buckets_[key] = {i, i};
    ++buckets_[key].second;
    points_.push_back(points[order[i]]);
  }
}

void StaticMap::for_each_in_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                                const std::function<void(const Eigen::Vector3d&)>& visit) const {
  if (!(lo.array() < hi.array()).all()) return;
  Eigen::Vector3d first, last;  // bucket indices, clamped to the keyable range
  for (int a = 0; a < 3; ++a) {
    const double limit = static_cast<double>(detail::kCellLimit);
    first[a] = std::clamp(std::floor(lo[a] / bucket_), -limit, limit - 1);
    last[a] = std::clamp(std::floor(hi[a] / bucket_), -limit, limit - 1);
  }
  const auto visit_bucket = [&](const std::pair<std::size_t, std::size_t>& range) {
    for (std::size_t i = range.first; i < range.second; ++i) {
      const Eigen::Vector3d& p = points_[i];
      if ((p.array() >= lo.array()).all() && (p.array() < hi.array()).all()) visit(p);
    }
  };
  const Eigen::Vector3d span = last - first + Eigen::Vector3d::Ones();
  if (span.prod() > static_cast<double>(buckets_.size())) {  // a box larger than the map
    for (const auto& [key, range] : buckets_) visit_bucket(range);
    return;
  }
  for (double x = first.x(); x <= last.x(); ++x) {
    for (double y = first.y(); y <= last.y(); ++y) {
      for (double z = first.z(); z <= last.z(); ++z) {
        const auto key = detail::grid_key(Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5) * bucket_, bucket_);
        const auto it = key ? buckets_.find(*key) : buckets_.end();
        if (it != buckets_.end()) visit_bucket(it->second);
      }
    }
  }
}

}  // namespace eco::workloads
