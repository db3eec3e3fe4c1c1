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
    const detail::EgoMotion moved = detail::advance_ego_motion(t, world_T_sensor);  // a moved origin hands back all
    const detail::Motion& motion = moved.motion;
    held_.assign(moved.displaced.begin(), moved.displaced.end());
    if (t.root != detail::kNone) {
      t.dissolve(t.root, &held_);
      t.root = detail::kNone;
    }
    held_ = detail::refine_overlap(t, motion, std::move(held_));  // a new, empty root on the box
    std::erase_if(held_, [&](const detail::StoredPoint& s) { return !t.keeps(s, motion.box); });
    t.rebuild_start_table(0);  // the paper's: every point from the root
    detail::reinsert(t, held_);
    detail::insert_scan(t, motion, scan);
  }

 private:
  std::vector<detail::StoredPoint> held_;
};

}  // namespace

std::unique_ptr<Method> make_octree_base(const Config& config) {
  return std::make_unique<OctreeBase>(config);
}

}  // namespace eco::baselines
