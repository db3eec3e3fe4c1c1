// Stage 5: the budget (Config::region.max_points). A frame is taken in with the whole region;
// when more points are held than the budget, the region shrinks about the sensor to the largest
// scale, in steps of 1 %, at which they fit, and the points outside leave.

#include "update/stages.hpp"

#include <array>
#include <cmath>

namespace eco::detail {
namespace {

constexpr int kSteps = 100;  // scales k / 100

/// The region at scale k / kSteps, k in [1, kSteps].
std::array<EgoRegion, kSteps + 1> scaled_regions(const Config& config, const Motion& motion) {
  std::array<EgoRegion, kSteps + 1> scaled{};
  for (int k = 1; k <= kSteps; ++k) {
    const Region r = config.region.sized(motion.region_size.growth, double(k) / kSteps);
    scaled[k] = *EgoRegion::at(r, motion.pose, motion.anchor);
  }
  return scaled;
}

// how near a step the gauge (x kSteps) must fall for contains() to decide: far above its rounding
// (1e-15 relative), so that a gauge this far from every step gives contains()'s verdict
constexpr double kNearStep = 1e-7;

/// The least k at which scaled[k] holds `p`; kSteps + 1 when none does. The gauge gives it; near a
/// step, where rounding could tell otherwise, contains() decides (membership grows with k: the
/// extents do).
int least_step(const std::array<EgoRegion, kSteps + 1>& scaled, const std::array<float, 3>& p) {
  const double x = scaled[kSteps].gauge(p) * kSteps;
  if (!(x <= kSteps + 1)) return kSteps + 1;  // beyond the whole region (or an extent of 0)
  int k = int(std::clamp(std::ceil(x), 1.0, double(kSteps + 1)));
  if (double(k) - x > kNearStep && x - double(k - 1) > kNearStep) return k;
  while (k <= kSteps && !scaled[k].contains(p)) ++k;
  while (k > 1 && scaled[k - 1].contains(p)) --k;
  return k;
}

/// How many held points each least step has, over the whole tree.
std::array<std::size_t, kSteps + 2> count_by_step(const Tree& tree, const std::array<EgoRegion, kSteps + 1>& scaled) {
  std::array<std::size_t, kSteps + 2> counts{};
  auto walk = [&](auto&& self, std::uint32_t id) -> void {
    const Node& n = tree.nodes()[id];
    if (n.count == 0) return;
    if (n.leaf) {
      tree.points().for_each(n.link, n.count, [&](const StoredPoint& s) { ++counts[least_step(scaled, s.p)]; });
      return;
    }
    tree.nodes().for_each_child(id, [&](int, std::uint32_t ch) { self(self, ch); });
  };
  walk(walk, tree.root());
  return counts;
}

}  // namespace

void keep_to_budget(Tree& tree, DensityCells* density, UpdateStats& stats) {
  const std::uint32_t budget = tree.config().region.max_points;
  if (budget == 0 || tree.size() <= budget) return;
  Motion narrowed = tree.motion();
  const auto scaled = scaled_regions(tree.config(), narrowed);
  const auto counts = count_by_step(tree, scaled);
  int fits = 0;  // the largest k whose region holds at most the budget
  for (std::size_t held = 0; fits < kSteps && held + counts[fits + 1] <= budget; ++fits) held += counts[fits + 1];
  narrowed.region = fits > 0 ? scaled[fits] : EgoRegion::nothing();
  narrowed.region_moved = true;
  narrowed.region_size.scale = double(fits) / kSteps;
  UpdateStats pruning;
  prune_shift_out(tree, density, narrowed, pruning);
  stats.over_budget += pruning.pruned;
  stats.region_tested += pruning.region_tested;
  tree.narrow_region(*narrowed.region, narrowed.region_size);
}

}  // namespace eco::detail
