#pragma once
// Moving objects' trails, measured with SemanticKITTI labels (moving classes 252-259): which held
// points were scanned on a moving object, and how many frames ago. A held point is matched to the
// scan point it came from by world position on a millimetre grid (a stored point is within
// 0.25 mm of its world point), trying the 26 cells around when rounding put it next door.

#include <eco/types.hpp>

#include <Eigen/Geometry>

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace eco::bench {

class TrailMeter {
 public:
  /// Moving points held more than `stale_after` frames after they were scanned count as trail.
  /// Scan points farther than `reach` [m] from the sensor on an axis are not remembered (a map of
  /// box side L holds none beyond L / 2).
  TrailMeter(double reach, std::size_t stale_after = 5) : reach_(reach), stale_after_(stale_after) {}

  /// Remembers frame `frame`'s points (sensor frame, at `world_T_sensor`) and their labels.
  void add_scan(std::size_t frame, const Eigen::Isometry3d& world_T_sensor, const std::vector<Eigen::Vector3f>& points,
                const std::vector<std::uint32_t>& labels);

  struct Census {
    std::size_t moving = 0;   ///< held points scanned on a moving object
    std::size_t trail = 0;    ///< of those, scanned more than stale_after frames before `now`
    std::size_t fixed = 0;    ///< held points scanned on anything else (static)
    std::size_t unknown = 0;  ///< held points matched to no remembered scan point
  };
  /// What the `held` points (world) are at frame `now`.
  [[nodiscard]] Census census(const std::vector<Eigen::Vector3d>& held, std::size_t now) const;
  /// How many static points of `reference` (world) are missing from `held`.
  [[nodiscard]] std::size_t static_missing(const std::vector<Eigen::Vector3d>& reference,
                                           const std::vector<Eigen::Vector3d>& held) const;
  /// Forgets scan points farther than `reach` from `position` on an axis (no map holds them now).
  void forget_beyond(const Eigen::Vector3d& position);

 private:
  using Key = VoxelKey;  // hashed by std::hash<VoxelKey> (eco/types.hpp)
  struct Scanned {
    std::uint32_t frame;
    bool moving;
  };
  static Key key_of(const Eigen::Vector3d& world);
  /// The remembered scan point at `world`, or null.
  [[nodiscard]] const Scanned* find(const Eigen::Vector3d& world) const;

  double reach_;
  std::size_t stale_after_;
  std::unordered_map<Key, Scanned> scanned_;
};

}  // namespace eco::bench
