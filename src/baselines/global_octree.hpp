#pragma once
// The global-rooted incremental octree of i-Octree (Zhu et al., ICRA 2024), as its paper
// describes it: the root is placed around the first pose and never moves; when points arrive
// outside it, a new root twice the size is made with the old root as one of its children. Both
// i-Octree baselines are this tree; they differ in whether they delete what left the box.

#include "baselines/tree_method.hpp"

namespace eco::baselines {

class GlobalOctree : public TreeMethod {
 public:
  /// `deletes`: drop the points that left the box every frame (ioctree_target) or keep
  /// everything ever inserted (ioctree_global).
  GlobalOctree(std::string name, const Config& config, bool deletes);

  void update(const Eigen::Isometry3d& world_T_sensor, ScanView scan) override;

 protected:
  [[nodiscard]] bool holds_only_the_box() const override { return deletes_; }

 private:
  bool deletes_;
};

}  // namespace eco::baselines
