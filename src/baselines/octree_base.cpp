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
    detail::Tree& t = tree_;
    UpdateStats stats = detail::begin_update(t.config(), world_T_sensor, scan);
    auto [motion, held] = detail::advance_ego_motion(t, world_T_sensor, stats);  // a moved origin hands back all
    detail::prune_shift_out(t, motion, stats);  // what left the box or aged out
    t.take_points(held);                        // the rest, to be rebuilt from scratch
    held = detail::refine_overlap(t, motion, std::move(held), stats);  // a new, empty root on the box
    t.rebuild_start_table(0);  // the paper's: every point from the root
    detail::reinsert(t, held, stats);
    detail::insert_scan(t, motion, scan, stats);
  }
};

}  // namespace

std::unique_ptr<Method> make_octree_base(const Config& config) {
  return std::make_unique<OctreeBase>(config);
}

}  // namespace eco::baselines
