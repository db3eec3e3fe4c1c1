// `octree_base` (the paper's Octree_base): every frame, the octree is rebuilt from scratch out of
// the points in the current box — last frame's points that are still inside, plus the scan
// points the insert policy admits. The root is the box itself, as in the paper. The rebuild is
// in bulk: the kept points, then the admitted scan points, are partitioned top-down by octant
// (Tree::insert_batch), each node visited once per batch rather than once per point.
//
// `scan_only` is the paper's dynamic Octree_base: rebuilt from the current scan's in-box points
// alone, it forgets every earlier frame. It is the reference the dynamic workload's voxel maps are
// compared with (Chamfer): how far a map's memory of past frames (moving objects' trails) takes
// it from what the sensor sees now.

#include "baselines/makers.hpp"
#include "baselines/tree_method.hpp"
#include "update/stages.hpp"

namespace eco::baselines {
namespace {

Config rebuilt_from_the_box(Config config) {
  config.recentring = Recentring::Exact;  // the root cell is the box
  return config;
}

Config rebuilt_from_the_scan(Config config) {
  config = rebuilt_from_the_box(config);
  config.insert_policy = InsertPolicy::AllInBox;  // every scan point in the box, whatever came before
  config.max_age_frames = 0;
  config.clearing.enabled = false;  // nothing earlier to clear
  return config;
}

/// What a rebuild keeps of the last frame's points.
enum class Memory { PointsStillInTheBox, Nothing };

class OctreeBase final : public TreeMethod {
 public:
  OctreeBase(const Config& config, Memory memory)
      : TreeMethod(memory == Memory::Nothing ? "scan_only" : "octree_base",
                   memory == Memory::Nothing ? rebuilt_from_the_scan(config) : rebuilt_from_the_box(config)),
        memory_(memory) {}

  void update(const Eigen::Isometry3d& world_T_sensor, ScanView scan) override {
    detail::Tree& t = tree_;
    UpdateStats stats = detail::begin_update(t.config(), world_T_sensor, scan);
    detail::ClearingState* clearing = clearing_.get();
    detail::DensityCells* density = density_.get();
    if (clearing) detail::release_arrivals(t, density, *clearing, stats);  // the last update's arrivals into space seen empty
    auto [motion, held] = detail::advance_ego_motion(t, density, world_T_sensor, scan, stats);  // a moved origin hands back all
    if (memory_ == Memory::PointsStillInTheBox) {
      detail::prune_shift_out(t, density, motion, stats);  // what left the box or aged out
      if (clearing) detail::clear_free_space(t, density, *clearing, motion, scan, held, stats);  // what the scan sees through
      t.take_points(held);  // the rest, rebuilt from scratch
    } else {
      t.take_points(held);
      held.clear();                     // nothing earlier is kept
      if (density) density->clear();    // so no cell holds a point any more
    }
    held = detail::refine_overlap(t, motion, std::move(held), stats);  // a new, empty root on the box
    t.rebuild_start_table(0);  // the paper's: every point from the root
    detail::reinsert(t, held, stats);
    detail::insert_scan(t, density, motion, scan, clearing, stats);
  }

 private:
  Memory memory_;
};

}  // namespace

std::unique_ptr<Method> make_octree_base(const Config& config) {
  return std::make_unique<OctreeBase>(config, Memory::PointsStillInTheBox);
}

std::unique_ptr<Method> make_scan_only(const Config& config) {
  return std::make_unique<OctreeBase>(config, Memory::Nothing);
}

}  // namespace eco::baselines
