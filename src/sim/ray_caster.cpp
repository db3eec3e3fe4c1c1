#include "sim/ray_caster.hpp"

#include <eco/io/kitti.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace eco::sim {

namespace {

constexpr std::uint32_t kBox = 0u << 30, kCylinder = 1u << 30, kSphere = 2u << 30;
constexpr std::uint32_t kKindMask = 3u << 30;

struct Footprint {
  Eigen::Vector2d lo, hi;
};

Footprint footprint(const Box& b) { return {b.lo.head<2>(), b.hi.head<2>()}; }
Footprint footprint(const Cylinder& c) {
  return {c.centre.array() - c.radius, c.centre.array() + c.radius};
}
Footprint footprint(const Sphere& s) {
  return {s.centre.head<2>().array() - s.radius, s.centre.head<2>().array() + s.radius};
}

// Calls visit(kind | index, footprint) for every static solid.
template <typename Visit>
void for_each_solid(const City& city, Visit&& visit) {
  for (std::size_t i = 0; i < city.boxes.size(); ++i) visit(kBox | static_cast<std::uint32_t>(i), footprint(city.boxes[i]));
  for (std::size_t i = 0; i < city.cylinders.size(); ++i) visit(kCylinder | static_cast<std::uint32_t>(i), footprint(city.cylinders[i]));
  for (std::size_t i = 0; i < city.spheres.size(); ++i) visit(kSphere | static_cast<std::uint32_t>(i), footprint(city.spheres[i]));
}

void keep_nearer(std::optional<Hit> hit, std::optional<Hit>& best, double& t_best) {
  if (hit && hit->t < t_best) {
    t_best = hit->t;
    best = hit;
  }
}

}  // namespace

RayCaster::RayCaster(const City& city, double cell) : city_(city), cell_(cell) {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector2d hi = -lo;
  for_each_solid(city, [&](std::uint32_t, const Footprint& f) {
    lo = lo.cwiseMin(f.lo);
    hi = hi.cwiseMax(f.hi);
  });
  if (lo.x() > hi.x()) lo = hi = Eigen::Vector2d::Zero();
  origin_ = lo;
  nx_ = std::max(1, static_cast<int>(std::ceil((hi.x() - lo.x()) / cell_)));
  ny_ = std::max(1, static_cast<int>(std::ceil((hi.y() - lo.y()) / cell_)));

  // Counting sort of (cell, item) pairs into first_/items_.
  const auto cells_of = [&](const Footprint& f, auto&& emit) {
    const auto index = [&](double v, double o, int n) {
      return std::clamp(static_cast<int>(std::floor((v - o) / cell_)), 0, n - 1);
    };
    for (int y = index(f.lo.y(), origin_.y(), ny_); y <= index(f.hi.y(), origin_.y(), ny_); ++y) {
      for (int x = index(f.lo.x(), origin_.x(), nx_); x <= index(f.hi.x(), origin_.x(), nx_); ++x) {
        emit(static_cast<std::size_t>(y) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(x));
      }
    }
  };
  first_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_) + 1, 0);
  for_each_solid(city, [&](std::uint32_t, const Footprint& f) {
    cells_of(f, [&](std::size_t c) { ++first_[c + 1]; });
  });
  for (std::size_t c = 1; c < first_.size(); ++c) first_[c] += first_[c - 1];
  items_.resize(first_.back());
  std::vector<std::uint32_t> fill(first_.begin(), first_.end() - 1);
  for_each_solid(city, [&](std::uint32_t item, const Footprint& f) {
    cells_of(f, [&](std::size_t c) { items_[fill[c]++] = item; });
  });
}

void RayCaster::hit_cell(const Ray& ray, std::size_t cell, std::optional<Hit>& best, double& t_best) const {
  for (std::uint32_t k = first_[cell]; k < first_[cell + 1]; ++k) {
    const std::uint32_t item = items_[k];
    const std::uint32_t index = item & ~kKindMask;
    switch (item & kKindMask) {
      case kBox: keep_nearer(intersect(ray, city_.boxes[index], t_best), best, t_best); break;
      case kCylinder: keep_nearer(intersect(ray, city_.cylinders[index], t_best), best, t_best); break;
      default: keep_nearer(intersect(ray, city_.spheres[index], t_best), best, t_best); break;
    }
  }
}

std::optional<Hit> RayCaster::cast_static(const Ray& ray, double t_max) const {
  // Clip the ray's ground track to the grid, then walk the cells it crosses (Amanatides-Woo).
  const Eigen::Vector2d o = ray.origin.head<2>(), d = ray.direction.head<2>();
  const Eigen::Vector2d size(nx_ * cell_, ny_ * cell_);
  double t0 = 0.0, t1 = t_max;
  for (int a = 0; a < 2; ++a) {
    const double lo = origin_[a] - o[a], hi = origin_[a] + size[a] - o[a];
    if (d[a] == 0.0) {
      if (lo > 0.0 || hi < 0.0) return std::nullopt;
      continue;
    }
    double ta = lo / d[a], tb = hi / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (t0 > t1) return std::nullopt;

  const Eigen::Vector2d entry = (o + t0 * d - origin_) / cell_;
  int cell[2] = {std::clamp(static_cast<int>(std::floor(entry.x())), 0, nx_ - 1),
                 std::clamp(static_cast<int>(std::floor(entry.y())), 0, ny_ - 1)};
  const int n[2] = {nx_, ny_};
  int step[2];
  double t_next[2], t_delta[2];
  for (int a = 0; a < 2; ++a) {
    constexpr double kNever = std::numeric_limits<double>::infinity();
    step[a] = d[a] > 0.0 ? 1 : -1;
    t_delta[a] = d[a] != 0.0 ? cell_ / std::abs(d[a]) : kNever;
    const double wall = origin_[a] + (cell[a] + (d[a] > 0.0 ? 1 : 0)) * cell_;
    t_next[a] = d[a] != 0.0 ? (wall - o[a]) / d[a] : kNever;
  }

  std::optional<Hit> best;
  double t_best = t_max;
  while (true) {
    hit_cell(ray, static_cast<std::size_t>(cell[1]) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(cell[0]),
             best, t_best);
    const int a = t_next[0] < t_next[1] ? 0 : 1;
    const double t_exit = t_next[a];
    if (t_best <= t_exit || t_exit > t1) break;  // nothing in a later cell can be nearer
    cell[a] += step[a];
    if (cell[a] < 0 || cell[a] >= n[a]) break;
    t_next[a] += t_delta[a];
  }
  return best;
}

std::optional<Hit> RayCaster::cast(const Ray& ray, double t_max, std::span<const TurnedBox> moving) const {
  std::optional<Hit> best;
  double t_best = t_max;
  if (ray.direction.z() < 0.0) {  // the road: the plane z = 0 under everything
    const double t = -ray.origin.z() / ray.direction.z();
    if (t < t_best) {
      t_best = t;
      best = Hit{t, Eigen::Vector3d::UnitZ(), io::label::kRoad, 0.15f};
    }
  }
  keep_nearer(cast_static(ray, t_best), best, t_best);
  for (const TurnedBox& car : moving) {
    const Eigen::Vector3d m = ray.origin - car.centre;  // bounding-sphere test first
    const double b = m.dot(ray.direction);
    const double r = car.half_size.norm();
    if (b > 0.0 && m.squaredNorm() > r * r) continue;
    if (m.squaredNorm() - b * b > r * r) continue;
    keep_nearer(intersect(ray, car, t_best), best, t_best);
  }
  return best;
}

}  // namespace eco::sim
