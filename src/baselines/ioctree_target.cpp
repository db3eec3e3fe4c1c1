// `ioctree_target` (the paper's i-Octree_target): the same global-rooted octree, bounded to the
// ego box: every frame it deletes what left the box and inserts what ECO inserts. Its root
// stays at the start of the drive, so its tree deepens as the robot drives away.

#include "baselines/global_octree.hpp"
#include "baselines/makers.hpp"

namespace eco::baselines {

std::unique_ptr<Method> make_ioctree_target(const Config& config) {
  return std::make_unique<GlobalOctree>("ioctree_target", config, /*deletes=*/true);
}

}  // namespace eco::baselines
