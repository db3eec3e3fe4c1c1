// eco.Stats and eco.UpdateStats: what the tree holds and what the last update did.

#include "bindings.hpp"
#include "records.hpp"

#include <eco/types.hpp>

namespace eco::python {

template <>
struct Record<Stats> {
  static constexpr const char* name = "Stats";
  static std::vector<Field<Stats>> fields() {
    return {
        field("points", &Stats::points, "points held"),
        field("nodes", &Stats::nodes, "live nodes, inner and leaf"),
        field("leaves", &Stats::leaves, "live leaves holding at least one point"),
        field("mean_leaf_depth", &Stats::mean_leaf_depth,
              "over non-empty leaves, weighted equally"),
        field("max_leaf_depth", &Stats::max_leaf_depth, "depth of the deepest non-empty leaf"),
        field("bytes", &Stats::bytes, "every byte the tree's pools reserve, free slots included"),
        field("snapshot_bytes", &Stats::snapshot_bytes,
              "bytes only snapshots keep alive (pages the tree replaced since), given back when "
              "the last snapshot holding them goes"),
    };
  }
};

template <>
struct Record<RegionExtents> {
  static constexpr const char* name = "RegionExtents";
  static std::vector<Field<RegionExtents>> fields() {
    using R = RegionExtents;
    return {
        field("radius", &R::radius, "[m] a ball's radius"),
        field("ahead", &R::ahead, "[m] an oriented box's extent ahead of the sensor"),
        field("behind", &R::behind, "[m] behind"),
        field("left", &R::left, "[m] to the left"),
        field("right", &R::right, "[m] to the right"),
        field("up", &R::up, "[m] above"),
        field("down", &R::down, "[m] below"),
        field("scale", &R::scale, "the budget's scale about the sensor (1: the whole region)"),
        field("speed", &R::speed, "[m/s] the smoothed speed the lookahead follows"),
    };
  }
};

template <>
struct Record<UpdateStats> {
  static constexpr const char* name = "UpdateStats";
  static std::vector<Field<UpdateStats>> fields() {
    using U = UpdateStats;
    return {
        field("scan_points", &U::scan_points, "points in the scan given"),
        field("inserted", &U::inserted, "scan points now held"),
        field("skipped_nonfinite", &U::skipped_nonfinite,
              "scan points with a NaN or infinite coordinate"),
        field("skipped_by_policy", &U::skipped_by_policy,
              "finite scan points outside Box(p_t) (or outside R_in)"),
        field("skipped_by_density", &U::skipped_by_density,
              "scan points refused by the density cap"),
        field("skipped_by_age", &U::skipped_by_age, "scan points already older than max_age_seconds"),
        field("pruned", &U::pruned, "held points that left the box or the region (R_out)"),
        field("region_tested", &U::region_tested,
              "held points tested one by one for the region's surface alone"),
        field("aged_out", &U::aged_out, "held points dropped by the age limit"),
        field("cleared", &U::cleared, "held points the scan saw through (free-space clearing)"),
        field("relinked_subtrees", &U::relinked_subtrees,
              "subtrees kept whole and attached to a new parent"),
        field("rebuilt_subtrees", &U::rebuilt_subtrees,
              "subtrees dissolved and their points re-inserted"),
        field("reinserted_points", &U::reinserted_points, "points moved by those rebuilds"),
        field("rebased", &U::rebased, "the precision origin moved this frame"),
        field("over_budget", &U::over_budget, "held points the budget's shrinking region let go"),
        field("region", &U::region, "the region held after this update (zeros for the cube)"),
    };
  }
};

void bind_results(py::module_& m) {
  bind_record<RegionExtents>(m, "The region held after an update: Config.region as its lookahead grew it and its "
                                "budget scaled it.", Access::ReadOnly);
  bind_record<Stats>(m, "What an EgoOctree holds now (EgoOctree.stats()).", Access::ReadOnly);
  bind_record<UpdateStats>(m, "What an update did (returned by EgoOctree.update()).",
                           Access::ReadOnly);
}

}  // namespace eco::python
