#pragma once
// The solids a city is made of, and where a ray first meets each of them.

#include <Eigen/Core>

#include <cstdint>
#include <optional>

namespace eco::sim {

/// What a ray hit: its distance along the (unit) ray and what the surface is.
struct Hit {
  double t = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  std::uint32_t label = 0;  ///< SemanticKITTI id
  float albedo = 0.0f;      ///< the surface's reflectivity in [0, 1]
};

struct Ray {
  Eigen::Vector3d origin;
  Eigen::Vector3d direction;  ///< unit length
};

struct Surface {
  std::uint32_t label = 0;
  float albedo = 0.5f;
};

struct Box {  // axis-aligned
  Eigen::Vector3d lo, hi;
  Surface surface;
};

struct Cylinder {  // vertical
  Eigen::Vector2d centre;
  double radius = 0.0, z_lo = 0.0, z_hi = 0.0;
  Surface surface;
};

struct Sphere {
  Eigen::Vector3d centre;
  double radius = 0.0;
  Surface surface;
};

/// A box turned by `yaw` about the vertical axis through `centre` (a driving car's body).
struct TurnedBox {
  Eigen::Vector3d centre;
  Eigen::Vector3d half_size;
  double yaw = 0.0;
  Surface surface;
};

/// Each returns the nearest hit with t in (0, t_max), if any.
[[nodiscard]] std::optional<Hit> intersect(const Ray& ray, const Box& box, double t_max);
[[nodiscard]] std::optional<Hit> intersect(const Ray& ray, const Cylinder& cylinder, double t_max);
[[nodiscard]] std::optional<Hit> intersect(const Ray& ray, const Sphere& sphere, double t_max);
[[nodiscard]] std::optional<Hit> intersect(const Ray& ray, const TurnedBox& box, double t_max);

}  // namespace eco::sim
