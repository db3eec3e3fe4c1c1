// `octree_base` (the paper's Octree_base): every frame, the octree is rebuilt from scratch out of
// the points in the current box — last frame's points that are still inside, plus the scan
// points the insert policy admits. The root is the box itself, as in the paper. The rebuild is
// in bulk: the kept points, then the admitted scan points, are partitioned top-down by octant
// (Tree::insert_batch), each node visited once per batch rather than once per point.

#include "baselines/makers.hpp"
#include "baselines/tree_method.hpp"
#include "update/stages.hpp"

namespace eco::baselines {
namespace {

Config rebuilt_from_the_box(Config config) {
  config.recentring = Recentring::Exact;  // the root cell is the box
  return config;
}

class OctreeBase final : public TreeMethod {
 public:
  explicit OctreeBase(const Config& config) : TreeMethod("octree_base", rebuilt_from_the_box(config)) {}

  void update(const Eigen::Isometry3d& world_T_sensor, ScanView scan) override {
    detail::check_update_arguments(world_T_sensor, "world_T_sensor", scan, tree_.cfg);
    detail::Tree& t = tree_;
    t.last = UpdateStats{};
    t.last.scan_points = scan.count;
    detail::advance_ego_motion(t, world_T_sensor);  // may move every point to t.moving (rebase)
    held_.clear();
    held_.swap(t.moving);
    if (t.root != detail::kNone) {
      t.dissolve(t.root, &held_);
      t.root = detail::kNone;
    }
    detail::refine_overlap(t);  // a new, empty root on the box
    t.rebuild_start_table(0);
    std::erase_if(held_, [&](const detail::StoredPoint& s) { return !t.keeps(s); });
    t.insert_batch(held_);
    detail::insert_shift_in(t, scan);
  }

 private:
  std::vector<detail::StoredPoint> held_;
};

}  // namespace

std::unique_ptr<Method> make_octree_base(const Config& config) {
  return std::make_unique<OctreeBase>(config);
}

}  // namespace eco::baselines
