#include "bench/trails.hpp"

#include <eco/io/kitti.hpp>

#include <cmath>
#include <unordered_set>

namespace eco::bench {

TrailMeter::Key TrailMeter::key_of(const Eigen::Vector3d& world) {
  return {std::llround(world.x() * 1e3), std::llround(world.y() * 1e3), std::llround(world.z() * 1e3)};
}

void TrailMeter::add_scan(std::size_t frame, const Eigen::Isometry3d& world_T_sensor,
                          const std::vector<Eigen::Vector3f>& points, const std::vector<std::uint32_t>& labels) {
  for (std::size_t i = 0; i < points.size() && i < labels.size(); ++i) {
    const Eigen::Vector3d local = points[i].cast<double>();
    if (!local.allFinite() || local.cwiseAbs().maxCoeff() > reach_ + 1.0) continue;  // + the pose's tilt
    scanned_[key_of(world_T_sensor * local)] = {std::uint32_t(frame), io::label::is_moving(labels[i])};
  }
}

const TrailMeter::Scanned* TrailMeter::find(const Eigen::Vector3d& world) const {
  const Key k = key_of(world);
  if (auto it = scanned_.find(k); it != scanned_.end()) return &it->second;
  for (std::int64_t dx = -1; dx <= 1; ++dx) {
    for (std::int64_t dy = -1; dy <= 1; ++dy) {
      for (std::int64_t dz = -1; dz <= 1; ++dz) {
        if (auto it = scanned_.find({k.x + dx, k.y + dy, k.z + dz}); it != scanned_.end()) return &it->second;
      }
    }
  }
  return nullptr;
}

TrailMeter::Census TrailMeter::census(const std::vector<Eigen::Vector3d>& held, std::size_t now) const {
  Census c;
  for (const Eigen::Vector3d& p : held) {
    const Scanned* s = find(p);
    if (s == nullptr) {
      ++c.unknown;
    } else if (s->moving) {
      ++c.moving;
      c.trail += now > s->frame + stale_after_ ? 1 : 0;
    } else {
      ++c.fixed;
    }
  }
  return c;
}

std::size_t TrailMeter::static_missing(const std::vector<Eigen::Vector3d>& reference,
                                       const std::vector<Eigen::Vector3d>& held) const {
  std::unordered_set<Key> present;
  for (const Eigen::Vector3d& p : held) present.insert(key_of(p));
  std::size_t missing = 0;
  for (const Eigen::Vector3d& p : reference) {
    const Scanned* s = find(p);
    if (s != nullptr && !s->moving && !present.contains(key_of(p))) ++missing;
  }
  return missing;
}

void TrailMeter::forget_beyond(const Eigen::Vector3d& position) {
  std::erase_if(scanned_, [&](const auto& entry) {
    const Key& k = entry.first;
    const Eigen::Vector3d p(double(k.x) * 1e-3, double(k.y) * 1e-3, double(k.z) * 1e-3);
    return (p - position).cwiseAbs().maxCoeff() > reach_ + 1.0;
  });
}

}  // namespace eco::bench
