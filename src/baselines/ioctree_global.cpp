// `ioctree_global` (the paper's i-Octree_global): the global-rooted incremental octree as
// i-Octree uses it for mapping: it takes in what ECO takes in and never deletes, so it grows
// with the distance driven.

#include "baselines/global_octree.hpp"
#include "baselines/makers.hpp"

namespace eco::baselines {

std::unique_ptr<Method> make_ioctree_global(const Config& config) {
  return std::make_unique<GlobalOctree>("ioctree_global", config, /*deletes=*/false);
}

}  // namespace eco::baselines
