#pragma once
// First hits of rays against the city: the road plane, the static solids through a uniform grid
// over the ground (walked cell by cell along the ray), and the moving cars of one instant.

#include "sim/city.hpp"
#include "sim/shapes.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace eco::sim {

class RayCaster {
 public:
  explicit RayCaster(const City& city, double cell = 8.0);

  /// The nearest hit closer than t_max, the cars of `moving` included.
  [[nodiscard]] std::optional<Hit> cast(const Ray& ray, double t_max,
                                        std::span<const TurnedBox> moving) const;

 private:
  [[nodiscard]] std::optional<Hit> cast_static(const Ray& ray, double t_max) const;
  void hit_cell(const Ray& ray, std::size_t cell, std::optional<Hit>& best, double& t_best) const;

  const City& city_;
  Eigen::Vector2d origin_;
  double cell_;
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> first_;  // items of cell c: items_[first_[c] .. first_[c + 1])
  std::vector<std::uint32_t> items_;  // kind in the top 2 bits, index in the rest
};

}  // namespace eco::sim
