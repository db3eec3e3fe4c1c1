// `scan_pass`: the physical limit of an update — transform every scan point, test it against the
// box, copy the admitted ones into a vector — and nothing else: no structure, no density cap, no
// point removed one by one. Each frame's points stay in their own vector with the intersection of
// every box since that frame (a box too, updated in O(1)): a point is held while it lies in it,
// which is exactly the contract's held set, so it passes the same oracle. A frame's vector is
// dropped once its box no longer meets its points. Queries scan every point: not timed.

#include "baselines/flat_frame.hpp"
#include "baselines/makers.hpp"

#include <algorithm>
#include <deque>
#include <utility>

namespace eco::baselines {
namespace {

class ScanPass final : public Method {
 public:
  explicit ScanPass(const Config& config) : frame_(without_cap(config), "scan_pass") {}

  [[nodiscard]] std::string name() const override { return "scan_pass"; }
  [[nodiscard]] bool indexed() const override { return false; }

  void update(const Eigen::Isometry3d& world_T_sensor, ScanView scan) override {
    FlatFrame::Step step = frame_.advance(world_T_sensor, scan);
    const detail::Box& box = step.admission.box;
    if (step.shift) {  // rare (every ~2 km): re-express the held points, as ECO does
      for (Batch& b : batches_) {
        std::erase_if(b.points, [&](const auto& p) { return !b.alive.contains(p[0], p[1], p[2]); });
        b.bounds = {};
        for (auto& p : b.points) {
          p = detail::rebased(p, *step.shift);
          b.bounds.grow(p[0], p[1], p[2]);
        }
        b.alive = box;
      }
    }
    for (Batch& b : batches_) {
      for (int a = 0; a < 3; ++a) {
        b.alive.lo[a] = std::max(b.alive.lo[a], box.lo[a]);
        b.alive.hi[a] = std::min(b.alive.hi[a], box.hi[a]);
      }
    }
    std::erase_if(batches_, [&](Batch& b) {
      if (!b.bounds.empty() && !b.alive.misses(b.bounds)) return false;
      spare_ = std::move(b.points);  // a dropped frame's storage goes to the next: no frame pays for fresh pages
      return true;
    });
    Batch& fresh = batches_.emplace_back();
    fresh.points = std::move(spare_);
    fresh.points.clear();
    spare_ = {};
    fresh.alive = box;
    fresh.points.reserve(scan.count);
    step.admission.for_each(scan, step.stats, [&](const std::array<float, 3>& p, std::size_t) { fresh.points.push_back(p); });
    for (const auto& p : fresh.points) fresh.bounds.grow(p[0], p[1], p[2]);
  }

  std::size_t knn(const Eigen::Vector3d& query, std::span<Neighbor> out) const override {
    std::vector<Neighbor> all = with_distances(query);
    const std::size_t n = std::min(out.size(), all.size());
    std::partial_sort(all.begin(), all.begin() + std::ptrdiff_t(n), all.end(), nearer);
    std::copy(all.begin(), all.begin() + std::ptrdiff_t(n), out.begin());
    return n;
  }
  using Method::knn;
  [[nodiscard]] std::vector<Neighbor> radius(const Eigen::Vector3d& query, double r) const override {
    if (!(r >= 0.0)) throw std::invalid_argument("scan_pass radius: radius must be >= 0");
    std::vector<Neighbor> all = with_distances(query);
    std::erase_if(all, [&](const Neighbor& n) { return n.sq_dist > r * r; });
    std::sort(all.begin(), all.end(), nearer);
    return all;
  }
  [[nodiscard]] std::vector<Eigen::Vector3d> box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const override {
    const detail::Box b = frame_.closed_box(lo, hi);
    std::vector<Eigen::Vector3d> out;
    for_each_held([&](const std::array<float, 3>& p) {
      if (b.contains(p[0], p[1], p[2])) out.push_back(frame_.world(p));
    });
    return out;
  }
  [[nodiscard]] std::vector<VoxelKey> voxel_keys(double resolution) const override {
    return voxel_keys_of_points(frame_, held(), resolution);
  }
  [[nodiscard]] std::vector<Eigen::Vector3d> points() const override {
    std::vector<Eigen::Vector3d> out;
    for_each_held([&](const std::array<float, 3>& p) { out.push_back(frame_.world(p)); });
    return out;
  }
  [[nodiscard]] std::size_t size() const override { return held().size(); }
  [[nodiscard]] Stats stats() const override {
    Stats s;
    s.points = size();
    s.bytes = sizeof(*this) + frame_.bytes();
    for (const Batch& b : batches_) s.bytes += sizeof(Batch) + b.points.capacity() * sizeof(b.points[0]);
    return s;
  }
  [[nodiscard]] Eigen::Vector3d precision_origin() const override { return frame_.anchor(); }
  [[nodiscard]] std::string check_invariants() const override { return ""; }
  [[nodiscard]] const Config& config() const override { return frame_.config(); }
  [[nodiscard]] const Eigen::Isometry3d& pose() const override { return frame_.pose(); }

 private:
  struct Batch {
    std::vector<std::array<float, 3>> points;
    detail::Aabb bounds;
    detail::Box alive;  // every box since the frame: its points are held while inside
  };

  static Config without_cap(Config config) {
    config.density_cap = {};  // the pass is the reference of the capped runs too: it counts nothing
    return config;
  }

  template <class F>
  void for_each_held(F&& f) const {
    for (const Batch& batch : batches_) {
      for (const auto& p : batch.points) {
        if (batch.alive.contains(p[0], p[1], p[2])) f(p);
      }
    }
  }
  [[nodiscard]] std::vector<std::array<float, 3>> held() const {
    std::vector<std::array<float, 3>> out;
    for_each_held([&](const std::array<float, 3>& p) { out.push_back(p); });
    return out;
  }
  [[nodiscard]] std::vector<Neighbor> with_distances(const Eigen::Vector3d& query) const {
    if (!query.allFinite()) throw std::invalid_argument("scan_pass: query is not finite");
    const std::array<double, 3> q = frame_.local(query);
    std::vector<Neighbor> out;
    for_each_held([&](const std::array<float, 3>& p) { out.push_back(frame_.neighbor(q, p)); });
    return out;
  }

  FlatFrame frame_;
  std::deque<Batch> batches_;
  std::vector<std::array<float, 3>> spare_;  // the last dropped frame's storage, for the next frame
};

}  // namespace

std::unique_ptr<Method> make_scan_pass(const Config& config) { return std::make_unique<ScanPass>(config); }

}  // namespace eco::baselines
