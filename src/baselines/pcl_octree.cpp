// `pcl_octree`: Debian's PCL 1.13 octree (pcl::octree::OctreePointCloudSearch, the octree module
// only), kept incrementally over the same points ECO holds. Its leaves are voxels of side
// Config::voxel_size (the benchmark's voxel map resolution), aligned to the world grid.
//
// * Points that entered the box are added with addPointToCloud (the cloud grows, the octree
//   indexes it).
// * PCL removes whole voxels only (deleteVoxelAtPoint), so the points that left are found with
//   boxSearch over the slabs the box left behind; each voxel holding one is deleted and its
//   points still in the box are added back. The cloud keeps the removed points until they
//   outnumber the held ones; then the octree is rebuilt from the held points (amortised; counted
//   in the update).
// * The density cap is the same set of occupied cells the other flat baselines keep.
// * KNN and radius: PCL's own search, in float; the distances reported are recomputed in double
//   (as ECO's) from the points it returns.

#include "baselines/flat_frame.hpp"
#include "baselines/makers.hpp"

#include <pcl/octree/octree_search.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>

namespace eco::baselines {
namespace {

using Octree = pcl::octree::OctreePointCloudSearch<pcl::PointXYZ>;

class PclOctree final : public Method {
 public:
  explicit PclOctree(const Config& config)
      : frame_(config, "pcl_octree"), resolution_(config.voxel_size > 0 ? config.voxel_size : 0.1) {}

  [[nodiscard]] std::string name() const override { return "pcl_octree"; }

  void update(const Eigen::Isometry3d& world_T_sensor, ScanView scan) override {
    const detail::Box previous = frame_.box();
    const bool first = frame_.frames() == 0;
    FlatFrame::Step step = frame_.advance(world_T_sensor, scan);
    const detail::Box& box = step.admission.box;
    if (first || step.shift) {
      std::vector<std::array<float, 3>> kept;
      for (const auto& p : held()) {
        std::array<float, 3> q = p;
        if (step.shift) {
          q = detail::rebased(q, *step.shift);
        }
        if (box.contains(q[0], q[1], q[2])) kept.push_back(q);
      }
      for (const auto& p : kept) frame_.count(p);
      rebuild(kept);
    } else {
      remove_what_left(previous, box);
    }
    frame_.take_in(scan, step, [&](const std::array<float, 3>& p) {
      octree_->addPointToCloud(pcl::PointXYZ(p[0], p[1], p[2]), cloud_);
      alive_.push_back(true);
      ++held_count_;
    });
    if (cloud_->size() > 2 * held_count_ + 4096) rebuild(held());  // drop the dead points
  }

  std::size_t knn(const Eigen::Vector3d& query, std::span<Neighbor> out) const override {
    if (!query.allFinite()) throw std::invalid_argument("pcl_octree knn: query is not finite");
    if (out.empty() || held_count_ == 0) return 0;
    thread_local pcl::Indices indices;
    thread_local std::vector<float> sq_dists;
    const std::array<double, 3> q = frame_.local(query);
    const auto k = std::min<std::size_t>(out.size(), held_count_);
    octree_->nearestKSearch(pcl::PointXYZ(float(q[0]), float(q[1]), float(q[2])), int(k), indices, sq_dists);
    for (std::size_t i = 0; i < indices.size(); ++i) out[i] = neighbor(q, indices[i]);
    std::sort(out.begin(), out.begin() + std::ptrdiff_t(indices.size()), nearer);
    return indices.size();
  }
  using Method::knn;

  [[nodiscard]] std::vector<Neighbor> radius(const Eigen::Vector3d& query, double r) const override {
    if (!query.allFinite() || !(r >= 0.0)) throw std::invalid_argument("pcl_octree radius: bad query or radius");
    std::vector<Neighbor> out;
    if (held_count_ == 0) return out;
    const std::array<double, 3> q = frame_.local(query);
    pcl::Indices indices;
    std::vector<float> sq_dists;  // float: ask a little wider, decide in double
    octree_->radiusSearch(pcl::PointXYZ(float(q[0]), float(q[1]), float(q[2])), r * (1 + 1e-5) + 1e-5, indices,
                          sq_dists);
    for (const pcl::index_t i : indices) {
      const Neighbor n = neighbor(q, i);
      if (n.sq_dist <= r * r) out.push_back(n);
    }
    std::sort(out.begin(), out.end(), nearer);
    return out;
  }

  [[nodiscard]] std::vector<Eigen::Vector3d> box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const override {
    const detail::Box b = frame_.closed_box(lo, hi);
    std::vector<Eigen::Vector3d> out;
    if (held_count_ == 0) return out;
    for (const pcl::index_t i : search_box(b)) {
      const pcl::PointXYZ& p = (*cloud_)[std::size_t(i)];
      if (b.contains(p.x, p.y, p.z)) out.push_back(frame_.world({p.x, p.y, p.z}));
    }
    return out;
  }

  /// At the octree's own resolution: its occupied voxels (getOccupiedVoxelCenters); any other
  /// resolution: the held points.
  [[nodiscard]] std::vector<VoxelKey> voxel_keys(double res) const override {
    if (res != resolution_) return voxel_keys_of_points(frame_, held(), res);
    frame_.require_voxel_resolution(res);
    Octree::AlignedPointTVector centres;
    if (held_count_ > 0) octree_->getOccupiedVoxelCenters(centres);
    std::vector<VoxelKey> keys;
    keys.reserve(centres.size());
    const detail::WorldGrid grid = frame_.voxel_grid(res);
    for (const pcl::PointXYZ& c : centres) keys.push_back(voxel_key(grid, {c.x, c.y, c.z}));
    return keys;
  }
  [[nodiscard]] std::vector<Eigen::Vector3d> points() const override {
    std::vector<Eigen::Vector3d> out;
    for (const auto& p : held()) out.push_back(frame_.world(p));
    return out;
  }
  [[nodiscard]] std::size_t size() const override { return held_count_; }
  [[nodiscard]] Stats stats() const override {
    Stats s;
    s.points = held_count_;
    // PCL does not report its memory: count the cloud, the alive flags, one index per point in
    // the leaves and a leaf and branch node per occupied voxel (lower bounds of what it holds).
    std::size_t voxels = 0;
    if (octree_) voxels = octree_->getLeafCount() + octree_->getBranchCount();
    s.bytes = sizeof(*this) + frame_.bytes() + (cloud_ ? cloud_->points.capacity() * sizeof(pcl::PointXYZ) : 0) +
              alive_.capacity() / 8 + held_count_ * sizeof(pcl::index_t) + voxels * 2 * sizeof(void*);
    return s;
  }
  [[nodiscard]] Eigen::Vector3d precision_origin() const override { return frame_.anchor(); }
  [[nodiscard]] std::string check_invariants() const override {
    const std::vector<std::array<float, 3>> live = held();
    const std::string outside = frame_.outside_box(live);
    if (!outside.empty()) return outside;
    return live.size() == held_count_ ? "" : "held count differs from the live points";
  }
  [[nodiscard]] const Config& config() const override { return frame_.config(); }
  [[nodiscard]] const Eigen::Isometry3d& pose() const override { return frame_.pose(); }

 private:
  /// A fresh octree over `points`, its bounding box a cube on the world voxel grid around the box.
  void rebuild(const std::vector<std::array<float, 3>>& points) {
    cloud_ = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
    cloud_->reserve(points.size());
    for (const auto& p : points) cloud_->push_back(pcl::PointXYZ(p[0], p[1], p[2]));
    alive_.assign(points.size(), true);
    held_count_ = points.size();
    octree_ = std::make_unique<Octree>(resolution_);
    const detail::Box b = frame_.box();
    const double side = resolution_ * std::exp2(std::ceil(std::log2((frame_.config().box_side + 2 * resolution_) / resolution_)));
    std::array<double, 3> lo{};
    for (int a = 0; a < 3; ++a) {  // a voxel wall of the world grid just below the box
      lo[a] = double(detail::world_grid_index(frame_.anchor()[a], float(b.lo[a]), resolution_) - 1) * resolution_ -
              frame_.anchor()[a];
    }
    octree_->defineBoundingBox(lo[0], lo[1], lo[2], lo[0] + side, lo[1] + side, lo[2] + side);
    octree_->setInputCloud(cloud_);
    octree_->addPointsFromInputCloud();
  }

  /// Deletes every voxel holding a point that left the box, then adds back its points still in.
  void remove_what_left(const detail::Box& previous, const detail::Box& box) {
    if (held_count_ == 0) return;
    pcl::Indices in_voxel;
    for (const detail::Box& slab : slabs_left(previous, box)) {
      for (const pcl::index_t i : search_box(slab)) {
        const pcl::PointXYZ p = (*cloud_)[std::size_t(i)];
        if (!alive_[std::size_t(i)] || box.contains(p.x, p.y, p.z)) continue;
        in_voxel.clear();
        octree_->voxelSearch(p, in_voxel);
        octree_->deleteVoxelAtPoint(p);
        for (const pcl::index_t j : in_voxel) {
          const pcl::PointXYZ& q = (*cloud_)[std::size_t(j)];
          if (box.contains(q.x, q.y, q.z)) {
            octree_->addPointFromCloud(pcl::uindex_t(j), nullptr);
          } else {
            alive_[std::size_t(j)] = false;
            --held_count_;
            frame_.forget({q.x, q.y, q.z});
          }
        }
      }
    }
  }

  /// The parts of `previous` outside `box` (at most three slabs), closed and widened a little:
  /// the exact test is made on each point found.
  static std::vector<detail::Box> slabs_left(detail::Box previous, const detail::Box& box) {
    std::vector<detail::Box> out;
    for (int a = 0; a < 3; ++a) {
      if (previous.lo[a] < box.lo[a]) {
        detail::Box s = previous;
        s.hi[a] = std::min(previous.hi[a], box.lo[a]);
        out.push_back(s);
        previous.lo[a] = std::min(previous.hi[a], box.lo[a]);
      }
      if (previous.hi[a] > box.hi[a]) {
        detail::Box s = previous;
        s.lo[a] = std::max(previous.lo[a], box.hi[a]);
        out.push_back(s);
        previous.hi[a] = std::max(previous.lo[a], box.hi[a]);
      }
    }
    return out;
  }

  [[nodiscard]] pcl::Indices search_box(const detail::Box& b) const {
    constexpr double kWiden = 1e-3;  // float corners must not cut off a point on the face
    const Eigen::Vector3f lo(float(b.lo[0] - kWiden), float(b.lo[1] - kWiden), float(b.lo[2] - kWiden));
    const Eigen::Vector3f hi(float(b.hi[0] + kWiden), float(b.hi[1] + kWiden), float(b.hi[2] + kWiden));
    pcl::Indices found;
    octree_->boxSearch(lo, hi, found);
    return found;
  }

  [[nodiscard]] Neighbor neighbor(const std::array<double, 3>& q, pcl::index_t i) const {
    const pcl::PointXYZ& p = (*cloud_)[std::size_t(i)];
    return frame_.neighbor(q, {p.x, p.y, p.z});
  }

  [[nodiscard]] std::vector<std::array<float, 3>> held() const {
    std::vector<std::array<float, 3>> out;
    if (!cloud_) return out;
    out.reserve(held_count_);
    for (std::size_t i = 0; i < cloud_->size(); ++i) {
      if (alive_[i]) out.push_back({(*cloud_)[i].x, (*cloud_)[i].y, (*cloud_)[i].z});
    }
    return out;
  }

  FlatFrame frame_;
  double resolution_;
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud_;
  std::vector<bool> alive_;  // per cloud index: still held
  std::size_t held_count_ = 0;
  std::unique_ptr<Octree> octree_;
};

}  // namespace

std::unique_ptr<Method> make_pcl_octree(const Config& config) { return std::make_unique<PclOctree>(config); }

}  // namespace eco::baselines
