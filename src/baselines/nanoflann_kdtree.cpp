// `nanoflann`: the k-d tree a robotics engineer would reach for (Debian's libnanoflann-dev),
// rebuilt every frame over the points in the box. The held set is a flat array kept the way ECO
// keeps its points (same admission, same float offsets from the same precision origin), so the
// k-d tree answers over exactly the points ECO holds.

#include "baselines/makers.hpp"
#include "core/tree.hpp"
#include "update/admission.hpp"
#include "update/stages.hpp"

#include <nanoflann.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace eco::baselines {
namespace {

/// nanoflann's dataset interface over the held points. Coordinates are read as double so that
/// distances are computed exactly as ECO computes them (float point, double query).
struct HeldPoints {
  std::vector<std::array<float, 3>> p;

  [[nodiscard]] std::size_t kdtree_get_point_count() const { return p.size(); }
  [[nodiscard]] double kdtree_get_pt(std::size_t i, std::size_t axis) const { return double(p[i][axis]); }
  template <class Bbox>
  bool kdtree_get_bbox(Bbox&) const {
    return false;
  }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, HeldPoints, double>,
                                                   HeldPoints, 3, std::uint32_t>;

constexpr std::size_t kLeafSize = 10;  // nanoflann's default

const Config& supported(const Config& config) {
  config.validate();
  if (config.density_cap.enabled()) {
    throw std::invalid_argument("the nanoflann baseline has no density cap (density_cap.max_points = " +
                                std::to_string(config.density_cap.max_points) + ")");
  }
  if (config.max_age_frames > 0) {
    throw std::invalid_argument("the nanoflann baseline has no age limit (max_age_frames = " +
                                std::to_string(config.max_age_frames) + ")");
  }
  return config;
}

class NanoflannKdTree final : public Method {
 public:
  explicit NanoflannKdTree(const Config& config) : cfg_(supported(config)) {}

  [[nodiscard]] std::string name() const override { return "nanoflann"; }

  void update(const Eigen::Isometry3d& world_T_sensor, ScanView scan) override {
    detail::check_update_arguments(world_T_sensor, "world_T_sensor", scan, cfg_);
    const Eigen::Vector3d position = world_T_sensor.translation();
    const Eigen::Vector3d anchor = detail::precision_origin_for(position, anchor_, frames_ == 0);
    if (anchor != anchor_) {  // re-express against the new origin, as ECO does
      const Eigen::Vector3d shift = anchor_ - anchor;
      for (auto& p : held_.p) {
        for (int a = 0; a < 3; ++a) p[a] = float(double(p[a]) + shift[a]);
      }
      anchor_ = anchor;
    }
    detail::Admission admit{world_T_sensor, anchor_, box_around(position), std::nullopt};
    if (cfg_.insert_policy == InsertPolicy::ShiftInOnly && frames_ > 0) {
      admit.previous = box_around(pose_.translation());
    }
    std::erase_if(held_.p, [&](const std::array<float, 3>& p) { return !admit.box.contains(p[0], p[1], p[2]); });
    UpdateStats ignored;
    admit.for_each(scan, ignored, [&](const std::array<float, 3>& p) { held_.p.push_back(p); });
    pose_ = world_T_sensor;
    ++frames_;
    index_ = std::make_unique<KdTree>(3, held_, nanoflann::KDTreeSingleIndexAdaptorParams(kLeafSize));
  }

  std::size_t knn(const Eigen::Vector3d& query, std::span<Neighbor> out) const override {
    if (!query.allFinite()) throw std::invalid_argument("nanoflann knn: query is not finite");
    if (!index_ || out.empty() || held_.p.empty()) return 0;
    const std::size_t k = std::min(out.size(), held_.p.size());
    thread_local std::vector<std::uint32_t> indices;  // no allocation per query once warm
    thread_local std::vector<double> sq_dists;
    indices.resize(k);
    sq_dists.resize(k);
    const std::array<double, 3> q = local(query);
    const std::size_t found = index_->knnSearch(q.data(), k, indices.data(), sq_dists.data());
    for (std::size_t i = 0; i < found; ++i) out[i] = {world(held_.p[indices[i]]), sq_dists[i]};
    return found;
  }
  using Method::knn;

  [[nodiscard]] std::vector<Neighbor> radius(const Eigen::Vector3d& query, double r) const override {
    if (!query.allFinite() || !(r >= 0.0)) throw std::invalid_argument("nanoflann radius: bad query or radius");
    std::vector<Neighbor> out;
    if (!index_) return out;
    std::vector<std::pair<std::uint32_t, double>> found;
    const std::array<double, 3> q = local(query);
    // nanoflann keeps d2 < bound (strict); the contract is d2 <= r^2, so ask one ulp wider.
    const double bound = std::nextafter(r * r, std::numeric_limits<double>::infinity());
    index_->radiusSearch(q.data(), bound, found, nanoflann::SearchParams(32, 0.0f, true));
    for (const auto& [i, d2] : found) {
      if (d2 <= r * r) out.push_back({world(held_.p[i]), d2});
    }
    return out;
  }

  // A k-d tree has no box or voxel query of its own: a scan of the held points answers them.
  [[nodiscard]] std::vector<Eigen::Vector3d> box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const override {
    detail::Box b;
    b.half_open = false;
    const std::array<double, 3> l = local(lo), h = local(hi);
    b.lo = l;
    b.hi = h;
    std::vector<Eigen::Vector3d> out;
    for (const auto& p : held_.p) {
      if (b.contains(p[0], p[1], p[2])) out.push_back(world(p));
    }
    return out;
  }
  [[nodiscard]] std::vector<VoxelKey> voxel_keys(double resolution) const override {
    std::vector<VoxelKey> keys;
    keys.reserve(held_.p.size());
    for (const auto& p : held_.p) {
      keys.push_back({detail::world_grid_index(anchor_[0], p[0], resolution),
                      detail::world_grid_index(anchor_[1], p[1], resolution),
                      detail::world_grid_index(anchor_[2], p[2], resolution)});
    }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    return keys;
  }
  [[nodiscard]] std::vector<Eigen::Vector3d> points() const override {
    std::vector<Eigen::Vector3d> out;
    out.reserve(held_.p.size());
    for (const auto& p : held_.p) out.push_back(world(p));
    return out;
  }

  [[nodiscard]] std::size_t size() const override { return held_.p.size(); }
  [[nodiscard]] Stats stats() const override {
    Stats s;
    s.points = held_.p.size();
    s.bytes = sizeof(*this) + held_.p.capacity() * sizeof(held_.p[0]);
    if (index_) s.bytes += sizeof(KdTree) + index_->usedMemory(*index_);
    return s;  // a k-d tree: no octree nodes or leaf depths to report
  }
  [[nodiscard]] Eigen::Vector3d precision_origin() const override { return anchor_; }
  [[nodiscard]] std::string check_invariants() const override {
    if (frames_ == 0) return "";
    const detail::Box b = box_around(pose_.translation());
    for (const auto& p : held_.p) {
      if (!b.contains(p[0], p[1], p[2])) return "point outside the ego box";
    }
    return index_ && index_->size(*index_) == held_.p.size() ? "" : "k-d tree not built over the held points";
  }
  [[nodiscard]] const Config& config() const override { return cfg_; }
  [[nodiscard]] const Eigen::Isometry3d& pose() const override { return pose_; }

 private:
  [[nodiscard]] detail::Box box_around(const Eigen::Vector3d& position) const {
    return detail::ego_box(position, anchor_, cfg_.box_side);
  }
  [[nodiscard]] std::array<double, 3> local(const Eigen::Vector3d& w) const {
    return {w[0] - anchor_[0], w[1] - anchor_[1], w[2] - anchor_[2]};
  }
  [[nodiscard]] Eigen::Vector3d world(const std::array<float, 3>& p) const {
    return {anchor_[0] + double(p[0]), anchor_[1] + double(p[1]), anchor_[2] + double(p[2])};
  }

  Config cfg_;
  Eigen::Isometry3d pose_ = Eigen::Isometry3d::Identity();
  Eigen::Vector3d anchor_ = Eigen::Vector3d::Zero();
  std::size_t frames_ = 0;
  HeldPoints held_;
  std::unique_ptr<KdTree> index_;
};

}  // namespace

std::unique_ptr<Method> make_nanoflann(const Config& config) { return std::make_unique<NanoflannKdTree>(config); }

}  // namespace eco::baselines
