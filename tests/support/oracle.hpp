#pragma once
// A brute-force copy of what an EgoOctree must hold, written from the contract
// (include/eco/ego_octree.hpp) alone: a flat list of points, filtered and searched by exhaustive
// loops. It stores points the way the contract says they are stored (float offsets from the
// precision origin) so that every comparison can be exact.

#include <eco/config.hpp>
#include <eco/types.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace eco::test {

/// What the map keeps of earlier frames.
enum class Memory {
  TheBox,      ///< the contract: what is still in the box (and within the age limit)
  Everything,  ///< a global map (ioctree_global): nothing is ever dropped
  Nothing,     ///< a map rebuilt from the current scan alone (scan_only)
};

/// The per-point attributes of a test scan (each empty or one per point).
struct ScanAttributes {
  std::vector<std::uint32_t> ids;
  std::vector<float> intensities;
  std::vector<double> times;
};

/// A test scan with per-point attributes, as the tree and the oracle take it.
struct AttributedScan {
  std::vector<Eigen::Vector3f> points;
  ScanAttributes attributes;
  [[nodiscard]] ScanView view() const {
    ScanView v(points);
    v.ids = attributes.ids.data();
    v.intensities = attributes.intensities.data();
    v.times = attributes.times.data();
    return v;
  }
};

class Oracle {
 public:
  explicit Oracle(const Config& config, Memory memory = Memory::TheBox) : cfg_(config), memory_(memory) {}

  /// Mirrors one update. `origin` and `time_origin` are the precision and time origins the tree
  /// reports after the update; `attributes` those of the scan.
  void update(const Eigen::Isometry3d& pose, const std::vector<Eigen::Vector3f>& scan,
              const Eigen::Vector3d& origin, const ScanAttributes& attributes = {}, double time_origin = 0.0) {
    ++frame_;
    if (origin != origin_) {  // re-express held points against the new origin
      const Eigen::Vector3d shift = origin_ - origin;
      for (Held& h : held_) {
        for (int a = 0; a < 3; ++a) h.p[a] = float(double(h.p[a]) + shift[a]);
      }
      origin_ = origin;
    }
    const bool timed = cfg_.attributes.time;
    if (timed) {
      for (const double t : attributes.times) latest_ = std::max(latest_, t);
      for (Held& h : held_) h.time = float(double(h.time) + (time_origin_ - time_origin));
      time_origin_ = time_origin;
    }
    // the age limit in seconds: stored offset f is aged when f < (latest - max age) - time origin
    const double time_cutoff = cfg_.max_age_seconds > 0.0 ? latest_ - cfg_.max_age_seconds - time_origin_
                                                          : -std::numeric_limits<double>::infinity();
    const bool had_box = frame_ > 1;
    const Eigen::Vector3d previous = position_;
    position_ = pose.translation();
    size_region(had_box ? (position_ - previous).norm() : 0.0, attributes.times);
    const std::uint32_t age = cfg_.max_age_frames;
    const std::uint32_t cutoff = age > 0 && frame_ > age ? frame_ - age : 0;
    if (memory_ == Memory::TheBox) {
      std::erase_if(held_, [&](const Held& h) {
        return !in_box(position_, h.p) || !in_region(pose, h.p) || h.stamp < cutoff || double(h.time) < time_cutoff;
      });
    } else if (memory_ == Memory::Nothing) {
      held_.clear();
    }
    if (cfg_.clearing.enabled) clear_free_space(pose, scan);

    const Eigen::Matrix3d r = pose.linear();
    const Eigen::Vector3d t = pose.translation();
    std::map<Cell, std::uint32_t> density = density_counts();
    for (std::size_t i = 0; i < scan.size(); ++i) {
      const Eigen::Vector3f& s = scan[i];
      if (!s.allFinite()) continue;
      const Eigen::Vector3d w = r * s.cast<double>() + t;
      const std::array<float, 3> f{float(w[0] - origin_[0]), float(w[1] - origin_[1]),
                                   float(w[2] - origin_[2])};
      if (!in_box(position_, f) || !in_region(pose, f)) continue;
      if (cfg_.insert_policy == InsertPolicy::ShiftInOnly && memory_ != Memory::Nothing && had_box &&
          in_box(previous, f)) {
        continue;
      }
      const float time = timed ? float(attributes.times[i] - time_origin_) : 0.0f;
      if (double(time) < time_cutoff) continue;  // older than the limit already
      if (cfg_.density_cap.enabled()) {  // the first points to reach a full cell are the ones kept
        std::uint32_t& held_there = density[cell_of(f)];
        if (held_there >= cfg_.density_cap.max_points) continue;
        ++held_there;
      }
      held_.push_back({f, age > 0 ? frame_ : 0, cfg_.attributes.ids ? attributes.ids[i] : 0u,
                       cfg_.attributes.intensity ? attributes.intensities[i] : 0.0f, time, frame_});
    }
    keep_to_budget(pose);
  }

  /// The region's growth [m] and budget scale after the last update (Config::region).
  [[nodiscard]] double region_growth() const { return growth_; }
  [[nodiscard]] double region_scale() const { return scale_; }

  /// Held points in world coordinates, sorted.
  [[nodiscard]] std::vector<Eigen::Vector3d> points() const {
    std::vector<Eigen::Vector3d> out;
    for (const Held& h : held_) out.push_back(world(h.p));
    sort_points(out);
    return out;
  }

  /// Held points in world coordinates with their attributes (times as the tree returns them),
  /// sorted by point, then id.
  [[nodiscard]] std::vector<HeldPoint> points_with_attributes() const {
    std::vector<HeldPoint> out;
    for (const Held& h : held_) {
      out.push_back({world(h.p), {h.id, h.intensity, cfg_.attributes.time ? time_origin_ + double(h.time) : 0.0}});
    }
    sort_held(out);
    return out;
  }
  static void sort_held(std::vector<HeldPoint>& v) {
    std::sort(v.begin(), v.end(), [](const HeldPoint& a, const HeldPoint& b) {
      if (a.point != b.point) {
        return std::lexicographical_compare(a.point.data(), a.point.data() + 3, b.point.data(), b.point.data() + 3);
      }
      return a.attributes.id < b.attributes.id;
    });
  }

  /// The k smallest squared distances from `query` (world), ascending.
  [[nodiscard]] std::vector<double> knn_sq_dists(const Eigen::Vector3d& query, std::size_t k) const {
    std::vector<double> d = all_sq_dists(query);
    std::sort(d.begin(), d.end());
    d.resize(std::min(k, d.size()));
    return d;
  }

  /// Held points within `radius` of `query` (world), as sorted world points.
  [[nodiscard]] std::vector<Eigen::Vector3d> radius(const Eigen::Vector3d& query, double radius) const {
    std::vector<Eigen::Vector3d> out;
    for (const Held& h : held_) {
      if (sq_dist(query, h.p) <= radius * radius) out.push_back(world(h.p));
    }
    sort_points(out);
    return out;
  }

  /// Held points in the closed world box [lo, hi], sorted.
  [[nodiscard]] std::vector<Eigen::Vector3d> box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
    std::vector<Eigen::Vector3d> out;
    for (const Held& h : held_) {
      bool in = true;
      for (int a = 0; a < 3; ++a) {
        const double v = double(h.p[a]);
        in = in && v >= lo[a] - origin_[a] && v <= hi[a] - origin_[a];
      }
      if (in) out.push_back(world(h.p));
    }
    sort_points(out);
    return out;
  }

  /// Held points in the closed box [lo, hi] of the axes `world_T_box`: d = f - the box's origin
  /// (both from the precision origin), turned into the box's axes, against lo and hi.
  [[nodiscard]] std::vector<Eigen::Vector3d> oriented_box(const Eigen::Isometry3d& world_T_box, const Eigen::Vector3d& lo,
                                                          const Eigen::Vector3d& hi) const {
    const Eigen::Matrix3d to_local = world_T_box.linear().transpose();
    const Eigen::Vector3d centre = world_T_box.translation() - origin_;
    std::vector<Eigen::Vector3d> out;
    for (const Held& h : held_) {
      const Eigen::Vector3d l = to_local * (Eigen::Vector3d(double(h.p[0]), double(h.p[1]), double(h.p[2])) - centre);
      if ((l.array() >= lo.array()).all() && (l.array() <= hi.array()).all()) out.push_back(world(h.p));
    }
    sort_points(out);
    return out;
  }

  [[nodiscard]] std::vector<VoxelKey> voxel_keys(double res) const {
    std::vector<VoxelKey> keys;
    for (const Held& h : held_) {
      keys.push_back({index(0, h.p[0], res), index(1, h.p[1], res), index(2, h.p[2], res)});
    }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    return keys;
  }

  /// The squared distance the contract defines between a world query and a world point the tree
  /// returned (both re-expressed against the precision origin, as stored).
  [[nodiscard]] double sq_dist_to_world(const Eigen::Vector3d& query, const Eigen::Vector3d& p) const {
    const std::array<float, 3> f{float(p[0] - origin_[0]), float(p[1] - origin_[1]), float(p[2] - origin_[2])};
    return sq_dist(query, f);
  }

  [[nodiscard]] std::size_t size() const { return held_.size(); }
  [[nodiscard]] const Eigen::Vector3d& position() const { return position_; }

  static void sort_points(std::vector<Eigen::Vector3d>& v) {
    std::sort(v.begin(), v.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
      return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    });
  }

 private:
  struct Held {
    std::array<float, 3> p;
    std::uint32_t stamp;
    std::uint32_t id;
    float intensity;
    float time;  // seconds from time_origin_
    std::uint32_t arrived;  // the update that brought it (clearing.arrivals)
  };

  /// A scan as clearing reads it: its returns' ranges by pixel (row, column), and the pose it was
  /// taken at.
  struct SeenScan {
    std::map<std::pair<int, int>, std::vector<double>> ranges_at;
    Eigen::Isometry3d pose;
    std::uint32_t frame;
  };
  [[nodiscard]] SeenScan seen_scan(const Eigen::Isometry3d& pose, const std::vector<Eigen::Vector3f>& scan) const {
    SeenScan seen{{}, pose, frame_};
    for (const Eigen::Vector3f& s : scan) {
      if (!s.allFinite()) continue;
      double range = 0.0;
      int row = 0, column = 0;
      if (pixel(s.cast<double>(), row, column, range)) seen.ranges_at[{row, column}].push_back(range);
    }
    return seen;
  }
  /// Whether `scan` sees through held point `h`: it is in the sensor's image, some return came
  /// back in each row (in the image) of its pixel and the 8 around it, and every one of those lies
  /// more than the margin beyond it.
  [[nodiscard]] bool sees_through(const SeenScan& scan, const Held& h) const {
    const Eigen::Vector3d stored(double(h.p[0]), double(h.p[1]), double(h.p[2]));
    const Eigen::Vector3d v = scan.pose.linear().transpose() * (origin_ - scan.pose.translation() + stored);
    double range = 0.0;
    int row = 0, column = 0;
    if (!pixel(v, row, column, range)) return false;
    const int columns = int(std::ceil(360.0 / cfg_.sensor.horizontal_resolution));
    const int rows = cfg_.sensor.rows();
    // the columns around it, wrapping around the circle (fewer than three in a narrow image)
    const std::set<int> around{(column + columns - 1) % columns, column, (column + 1) % columns};
    double nearest = std::numeric_limits<double>::infinity();
    std::array<bool, 3> row_returned{row == 0, false, row + 1 == rows};  // rows past the edge need none
    for (int up = -1; up <= 1; ++up) {
      for (const int c : around) {
        const auto rays = scan.ranges_at.find({row + up, c});
        if (rays == scan.ranges_at.end()) continue;
        for (const double r : rays->second) nearest = std::min(nearest, r);
        row_returned[std::size_t(up + 1)] = true;
      }
    }
    const bool every_row = row_returned[0] && row_returned[1] && row_returned[2];
    return every_row && nearest > range + cfg_.clearing.margin;
  }
  /// Free-space clearing as include/eco/config.hpp words it, ray by ray: a held point goes when
  /// this scan sees through it or, with arrivals, when it came in the last update and the scan
  /// before that one saw through it.
  void clear_free_space(const Eigen::Isometry3d& pose, const std::vector<Eigen::Vector3f>& scan) {
    SeenScan now = seen_scan(pose, scan);
    const bool arrivals = cfg_.clearing.arrivals && scans_.size() == 2 && scans_.front().frame + 2 == frame_;
    std::erase_if(held_, [&](const Held& h) {
      return sees_through(now, h) || (arrivals && h.arrived + 1 == frame_ && sees_through(scans_.front(), h));
    });
    if (!cfg_.clearing.arrivals) return;
    scans_.push_back(std::move(now));
    if (scans_.size() > 2) scans_.erase(scans_.begin());
  }
  /// The range image pixel of sensor-frame point v (SensorModel's formulas); false outside it.
  [[nodiscard]] bool pixel(const Eigen::Vector3d& v, int& row, int& column, double& range) const {
    const SensorModel& m = cfg_.sensor;
    range = v.norm();
    if (range > m.max_range) return false;
    const double elevation = std::atan2(v.z(), std::hypot(v.x(), v.y())) * 180.0 / M_PI;
    const double azimuth = std::atan2(v.y(), v.x()) * 180.0 / M_PI;
    if (elevation < m.vertical_fov_min || elevation >= m.vertical_fov_max) return false;
    const int rows = int(std::ceil((m.vertical_fov_max - m.vertical_fov_min) / m.vertical_resolution));
    const int columns = int(std::ceil(360.0 / m.horizontal_resolution));
    row = std::min(rows - 1, int(std::floor((elevation - m.vertical_fov_min) / m.vertical_resolution)));
    column = int(std::floor((azimuth + 180.0) / m.horizontal_resolution)) % columns;
    return true;
  }

  /// Config::region at `pose`, as the contract words it: d = f - the sensor (both from the
  /// precision origin), turned into the region's axes, against the extents (closed).
  /// The lookahead (Config::region): the speed from the distance `moved` over the time between
  /// the scans' latest points (or frame_period), smoothed by 0.3 a frame; the growth set to 1.25x
  /// speed x lookahead when that exceeds it or falls under 1/1.25^2 of it, at most what the cube
  /// holds. Each frame starts from the whole region (scale 1).
  void size_region(double moved, const std::vector<double>& times) {
    scale_ = 1.0;
    double time = std::numeric_limits<double>::quiet_NaN();
    for (const double t : times) {
      if (std::isfinite(t) && (std::isnan(time) || t > time)) time = t;
    }
    const double last_time = last_scan_time_;
    last_scan_time_ = time;
    const Region& r = cfg_.region;
    if (r.lookahead == 0.0) return;
    const bool timed = std::isfinite(time) && std::isfinite(last_time) && time > last_time;
    speed_ += 0.3 * (moved / (timed ? time - last_time : r.frame_period) - speed_);
    const double asked = speed_ * r.lookahead;
    if (asked > growth_ || asked * 1.25 * 1.25 < growth_) growth_ = std::min(asked * 1.25, r.max_growth(cfg_.box_side / 2));
  }

  /// The budget (Config::region.max_points): while more are held, the largest scale k / 100 at
  /// which the region holds at most the budget, tried from the whole region down; none: nothing.
  void keep_to_budget(const Eigen::Isometry3d& pose) {
    const std::uint32_t budget = cfg_.region.max_points;
    if (budget == 0 || held_.size() <= budget) return;
    int k = 100;
    for (; k > 0; --k) {
      scale_ = k / 100.0;
      const auto inside = std::count_if(held_.begin(), held_.end(), [&](const Held& h) { return in_region(pose, h.p); });
      if (std::size_t(inside) <= budget) break;
    }
    scale_ = k / 100.0;
    std::erase_if(held_, [&](const Held& h) { return k == 0 || !in_region(pose, h.p); });
  }

  [[nodiscard]] bool in_region(const Eigen::Isometry3d& pose, const std::array<float, 3>& f) const {
    if (cfg_.region.shape == RegionShape::Cube) return true;
    Region r = cfg_.region;  // grown ahead (a ball: all round), then scaled about the sensor
    (r.shape == RegionShape::Ball ? r.radius : r.ahead) += growth_;
    for (double* e : {&r.radius, &r.ahead, &r.behind, &r.left, &r.right, &r.up, &r.down}) *e *= scale_;
    const Eigen::Vector3d d = Eigen::Vector3d(double(f[0]), double(f[1]), double(f[2])) - (pose.translation() - origin_);
    if (r.shape == RegionShape::Ball) return d.squaredNorm() <= r.radius * r.radius;
    Eigen::Matrix3d turn = pose.linear();
    if (r.turn_with == TurnWith::Yaw) {
      turn = Eigen::AngleAxisd(std::atan2(turn(1, 0), turn(0, 0)), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    }
    const Eigen::Matrix3d to_local = turn.transpose();
    const Eigen::Vector3d l = to_local * d;
    return l.x() >= -r.behind && l.x() <= r.ahead && l.y() >= -r.right && l.y() <= r.left && l.z() >= -r.down &&
           l.z() <= r.up;
  }

  [[nodiscard]] bool in_box(const Eigen::Vector3d& centre, const std::array<float, 3>& f) const {
    for (int a = 0; a < 3; ++a) {
      const double lo = (centre[a] - origin_[a]) - cfg_.box_side / 2;
      const double hi = lo + cfg_.box_side;
      if (double(f[a]) < lo || double(f[a]) >= hi) return false;
    }
    return true;
  }
  [[nodiscard]] Eigen::Vector3d world(const std::array<float, 3>& f) const {
    return {origin_[0] + double(f[0]), origin_[1] + double(f[1]), origin_[2] + double(f[2])};
  }
  [[nodiscard]] double sq_dist(const Eigen::Vector3d& query, const std::array<float, 3>& f) const {
    double d2 = 0;
    for (int a = 0; a < 3; ++a) {
      const double d = double(f[a]) - (query[a] - origin_[a]);
      d2 += d * d;
    }
    return d2;
  }
  [[nodiscard]] std::vector<double> all_sq_dists(const Eigen::Vector3d& query) const {
    std::vector<double> d;
    for (const Held& h : held_) d.push_back(sq_dist(query, h.p));
    return d;
  }
  /// The contract's grid cell: the i with i*res - origin <= f < (i+1)*res - origin, walls in
  /// double (floor((origin + f) / res) up to its rounding).
  [[nodiscard]] std::int64_t index(int a, float f, double res) const {
    std::int64_t i = std::int64_t(std::floor((origin_[a] + double(f)) / res)) - 2;
    while (double(f) >= double(i + 1) * res - origin_[a]) ++i;
    return i;
  }
  /// A density cell: the grid indices of the cap's cell.
  using Cell = std::array<std::int64_t, 3>;
  [[nodiscard]] Cell cell_of(const std::array<float, 3>& f) const {
    const double r = cfg_.density_cap.cell_size;
    return {index(0, f[0], r), index(1, f[1], r), index(2, f[2], r)};
  }
  /// The held points of every density cell, counted one by one (empty while the cap is off).
  [[nodiscard]] std::map<Cell, std::uint32_t> density_counts() const {
    std::map<Cell, std::uint32_t> counts;
    if (!cfg_.density_cap.enabled()) return counts;
    for (const Held& h : held_) ++counts[cell_of(h.p)];
    return counts;
  }

  Config cfg_;
  Memory memory_ = Memory::TheBox;
  std::vector<Held> held_;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d position_ = Eigen::Vector3d::Zero();
  std::uint32_t frame_ = 0;
  std::vector<SeenScan> scans_;  // the last two updates' (clearing.arrivals), oldest first
  double latest_ = -std::numeric_limits<double>::infinity();  // the latest time taken in
  double speed_ = 0.0, growth_ = 0.0, scale_ = 1.0;  // Config::region's lookahead and budget
  double last_scan_time_ = std::numeric_limits<double>::quiet_NaN();
  double time_origin_ = 0.0;
};

}  // namespace eco::test
