// `nanoflann`: the k-d tree a robotics engineer would reach for (Debian's libnanoflann-dev),
// rebuilt every frame over the points in the box. The held set is a flat array kept the way ECO
// keeps its points (same admission, same float offsets from the same precision origin, the
// density cap as a set of occupied cells kept as points come and go), so the k-d tree answers
// over exactly the points ECO holds.

#include "baselines/flat_frame.hpp"
#include "baselines/makers.hpp"

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

class NanoflannKdTree final : public Method {
 public:
  explicit NanoflannKdTree(const Config& config) : frame_(config, "nanoflann") {}

  [[nodiscard]] std::string name() const override { return "nanoflann"; }

  void update(const Eigen::Isometry3d& world_T_sensor, ScanView scan) override {
    FlatFrame::Step step = frame_.advance(world_T_sensor, scan);
    if (step.shift) {  // re-express against the new origin, as ECO does
      for (auto& p : held_.p) {
        p = detail::rebased(p, *step.shift);
        frame_.count(p);
      }
    }
    const detail::Box& box = step.admission.box;
    std::erase_if(held_.p, [&](const std::array<float, 3>& p) {
      if (box.contains(p[0], p[1], p[2])) return false;
      frame_.forget(p);
      return true;
    });
    frame_.take_in(scan, step, [&](const std::array<float, 3>& p) { held_.p.push_back(p); });
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
    const std::array<double, 3> q = frame_.local(query);
    const std::size_t found = index_->knnSearch(q.data(), k, indices.data(), sq_dists.data());
    for (std::size_t i = 0; i < found; ++i) out[i] = {frame_.world(held_.p[indices[i]]), sq_dists[i], {}};
    return found;
  }
  using Method::knn;

  [[nodiscard]] std::vector<Neighbor> radius(const Eigen::Vector3d& query, double r) const override {
    if (!query.allFinite() || !(r >= 0.0)) throw std::invalid_argument("nanoflann radius: bad query or radius");
    std::vector<Neighbor> out;
    if (!index_) return out;
    std::vector<std::pair<std::uint32_t, double>> found;
    const std::array<double, 3> q = frame_.local(query);
    // nanoflann keeps d2 < bound (strict); the contract is d2 <= r^2, so ask one ulp wider.
    const double bound = std::nextafter(r * r, std::numeric_limits<double>::infinity());
    index_->radiusSearch(q.data(), bound, found, nanoflann::SearchParams(32, 0.0f, true));
    for (const auto& [i, d2] : found) {
      if (d2 <= r * r) out.push_back({frame_.world(held_.p[i]), d2, {}});
    }
    return out;
  }

  // A k-d tree has no box or voxel query of its own: a scan of the held points answers them.
  [[nodiscard]] std::vector<Eigen::Vector3d> box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const override {
    const detail::Box b = frame_.closed_box(lo, hi);
    std::vector<Eigen::Vector3d> out;
    for (const auto& p : held_.p) {
      if (b.contains(p[0], p[1], p[2])) out.push_back(frame_.world(p));
    }
    return out;
  }
  [[nodiscard]] std::vector<VoxelKey> voxel_keys(double resolution) const override {
    return voxel_keys_of_points(frame_, held_.p, resolution);
  }
  [[nodiscard]] std::vector<Eigen::Vector3d> points() const override {
    std::vector<Eigen::Vector3d> out;
    out.reserve(held_.p.size());
    for (const auto& p : held_.p) out.push_back(frame_.world(p));
    return out;
  }

  [[nodiscard]] std::size_t size() const override { return held_.p.size(); }
  [[nodiscard]] Stats stats() const override {
    Stats s;
    s.points = held_.p.size();
    s.bytes = sizeof(*this) + frame_.bytes() + held_.p.capacity() * sizeof(held_.p[0]);
    if (index_) s.bytes += sizeof(KdTree) + index_->usedMemory(*index_);
    return s;  // a k-d tree: no octree nodes or leaf depths to report
  }
  [[nodiscard]] Eigen::Vector3d precision_origin() const override { return frame_.anchor(); }
  [[nodiscard]] std::string check_invariants() const override {
    const std::string outside = frame_.outside_box(held_.p);
    if (!outside.empty() || frame_.frames() == 0) return outside;
    return index_ && index_->size(*index_) == held_.p.size() ? "" : "k-d tree not built over the held points";
  }
  [[nodiscard]] const Config& config() const override { return frame_.config(); }
  [[nodiscard]] const Eigen::Isometry3d& pose() const override { return frame_.pose(); }

 private:
  FlatFrame frame_;
  HeldPoints held_;
  std::unique_ptr<KdTree> index_;
};

}  // namespace

std::unique_ptr<Method> make_nanoflann(const Config& config) { return std::make_unique<NanoflannKdTree>(config); }

}  // namespace eco::baselines
