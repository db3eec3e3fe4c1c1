#include "sim/shapes.hpp"

#include <cmath>
#include <limits>

namespace eco::sim {

namespace {

// Slab test against an axis-aligned box; the normal is that of the face entered.
std::optional<Hit> slabs(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                         const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double t_max) {
  double t_enter = 0.0, t_exit = t_max;
  int axis = -1;
  for (int a = 0; a < 3; ++a) {
    if (direction[a] == 0.0) {
      if (origin[a] < lo[a] || origin[a] > hi[a]) return std::nullopt;
      continue;
    }
    const double inv = 1.0 / direction[a];
    double t0 = (lo[a] - origin[a]) * inv, t1 = (hi[a] - origin[a]) * inv;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > t_enter) {
      t_enter = t0;
      axis = a;
    }
    t_exit = std::min(t_exit, t1);
    if (t_enter > t_exit) return std::nullopt;
  }
  if (axis < 0) return std::nullopt;  // starts inside: a sensor never sits in a solid
  Hit hit;
  hit.t = t_enter;
  hit.normal = Eigen::Vector3d::Zero();
  hit.normal[axis] = direction[axis] > 0.0 ? -1.0 : 1.0;
  return hit;
}

std::optional<Hit> with_surface(std::optional<Hit> hit, const Surface& surface) {
  if (hit) {
    hit->label = surface.label;
    hit->albedo = surface.albedo;
  }
  return hit;
}

}  // namespace

std::optional<Hit> intersect(const Ray& ray, const Box& box, double t_max) {
  return with_surface(slabs(ray.origin, ray.direction, box.lo, box.hi, t_max), box.surface);
}

std::optional<Hit> intersect(const Ray& ray, const Cylinder& cylinder, double t_max) {
  const Eigen::Vector2d d = ray.direction.head<2>();
  const Eigen::Vector2d m = ray.origin.head<2>() - cylinder.centre;
  const double a = d.squaredNorm();
  const double b = m.dot(d);
  const double c = m.squaredNorm() - cylinder.radius * cylinder.radius;
  std::optional<Hit> best;
  if (a > 0.0 && b * b - a * c >= 0.0) {  // the side
    const double t = (-b - std::sqrt(b * b - a * c)) / a;
    const double z = ray.origin.z() + t * ray.direction.z();
    if (t > 0.0 && t < t_max && z >= cylinder.z_lo && z <= cylinder.z_hi) {
      const Eigen::Vector2d radial = (m + t * d) / cylinder.radius;
      best = Hit{t, {radial.x(), radial.y(), 0.0}};
    }
  }
  if (ray.direction.z() < 0.0 && ray.origin.z() > cylinder.z_hi) {  // the top
    const double t = (cylinder.z_hi - ray.origin.z()) / ray.direction.z();
    if (t > 0.0 && t < (best ? best->t : t_max) && (m + t * d).squaredNorm() <= cylinder.radius * cylinder.radius) {
      best = Hit{t, Eigen::Vector3d::UnitZ()};
    }
  }
  return with_surface(best, cylinder.surface);
}

std::optional<Hit> intersect(const Ray& ray, const Sphere& sphere, double t_max) {
  const Eigen::Vector3d m = ray.origin - sphere.centre;
  const double b = m.dot(ray.direction);
  const double c = m.squaredNorm() - sphere.radius * sphere.radius;
  const double disc = b * b - c;
  if (disc < 0.0) return std::nullopt;
  const double t = -b - std::sqrt(disc);
  if (t <= 0.0 || t >= t_max) return std::nullopt;
  return with_surface(Hit{t, (m + t * ray.direction) / sphere.radius}, sphere.surface);
}

std::optional<Hit> intersect(const Ray& ray, const TurnedBox& box, double t_max) {
  const double c = std::cos(box.yaw), s = std::sin(box.yaw);
  const auto to_box = [&](const Eigen::Vector3d& v) {  // rotate by -yaw
    return Eigen::Vector3d(c * v.x() + s * v.y(), -s * v.x() + c * v.y(), v.z());
  };
  auto hit = slabs(to_box(ray.origin - box.centre), to_box(ray.direction), -box.half_size,
                   box.half_size, t_max);
  if (hit) {
    const Eigen::Vector3d n = hit->normal;
    hit->normal = {c * n.x() - s * n.y(), s * n.x() + c * n.y(), n.z()};
  }
  return with_surface(hit, box.surface);
}

}  // namespace eco::sim
