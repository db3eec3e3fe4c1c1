// The optional knobs against the oracle: the density cap (at most N points per world cell of
// side r) and the age limit (points older than A frames dropped), alone and together, in both
// re-centring modes.

#include "support/compare.hpp"
#include "support/streams.hpp"

namespace eco::test {
namespace {

struct Knobs {
  double cap_cell;
  std::uint32_t cap_points;
  std::uint32_t max_age;
};

using Params = std::tuple<Recentring, Motion, Cloud, int>;
const Knobs kKnobs[] = {{0.0, 0, 3}, {1.0, 2, 0}, {0.37, 1, 5}, {2.5, 7, 1}};

class DensityAge : public ::testing::TestWithParam<Params> {};

TEST_P(DensityAge, MatchesBruteForceEveryFrame) {
  const auto [recentring, motion, cloud, knob_index] = GetParam();
  const Knobs& k = kKnobs[knob_index];
  Config cfg;
  cfg.recentring = recentring;
  cfg.insert_policy = InsertPolicy::AllInBox;
  cfg.leaf_capacity = 6;
  cfg.density_cap = {k.cap_cell, k.cap_points};
  cfg.max_age_frames = k.max_age;
  EgoOctree tree(cfg);
  Oracle oracle(cfg);
  Stream stream(motion, cloud, cfg.box_side, 21u);
  std::mt19937 rng(8);
  std::size_t capped = 0, aged = 0;
  for (int t = 0; t < 25; ++t) {
    const auto scan = stream.scan(t);
    const UpdateStats& st = tree.update(stream.pose(t), scan);
    oracle.update(stream.pose(t), scan, tree.precision_origin());
    capped += st.skipped_by_density;
    aged += st.aged_out;
    expect_same_answers(tree, oracle, rng, "frame " + std::to_string(t));
    if (HasFatalFailure()) return;
  }
  if (k.cap_points > 0 && cloud != Cloud::Few) {
    EXPECT_GT(capped, 0u) << "the cap never bit";
  }
  if (k.max_age > 0 && motion == Motion::Still && cloud != Cloud::Few) {
    EXPECT_GT(aged, 0u) << "nothing aged";
  }
}

INSTANTIATE_TEST_SUITE_P(Knobs, DensityAge,
                         ::testing::Combine(::testing::Values(Recentring::Quantised, Recentring::Exact),
                                            ::testing::Values(Motion::Still, Motion::Smooth, Motion::Teleport),
                                            ::testing::Values(Cloud::Surfaces, Cloud::Duplicates, Cloud::Few),
                                            ::testing::Range(0, 4)));

/// The cell counts follow the points through every structural change: a drive that jumps farther
/// than the box and moves the precision origin (kilometres a frame), both re-centring modes.
TEST(DensityCap, CountsSurviveJumpsAndPrecisionOriginMoves) {
  for (const Recentring recentring : {Recentring::Quantised, Recentring::Exact}) {
    Config cfg;
    cfg.recentring = recentring;
    cfg.density_cap = {0.4, 2};
    cfg.max_age_frames = 6;
    cfg.leaf_capacity = 4;
    EgoOctree tree(cfg);
    Oracle oracle(cfg);
    Stream stream(Motion::Smooth, Cloud::Duplicates, cfg.box_side, 31u);
    std::mt19937 rng(5);
    bool rebased = false;
    for (int t = 0; t < 30; ++t) {
      Eigen::Isometry3d pose = stream.pose(t);
      if (t % 10 == 9) pose.translation().x() += 1500.0 * t;  // far, then back
      const auto scan = stream.scan(t);
      rebased = tree.update(pose, scan).rebased || rebased;
      oracle.update(pose, scan, tree.precision_origin());
      expect_same_answers(tree, oracle, rng, "frame " + std::to_string(t));
      if (HasFatalFailure()) return;
    }
    EXPECT_TRUE(rebased) << "the precision origin never moved";
  }
}

TEST(AgeLimit, StationaryScansStayBounded) {
  Config cfg;
  cfg.insert_policy = InsertPolicy::AllInBox;
  cfg.max_age_frames = 4;
  EgoOctree tree(cfg);
  Stream stream(Motion::Still, Cloud::Uniform, cfg.box_side, 2u);
  std::size_t most = 0;
  for (int t = 0; t < 60; ++t) {
    tree.update(stream.pose(t), stream.scan(t));
    most = std::max(most, tree.size());
  }
  EXPECT_LE(most, 5u * 252u);  // at most the last A + 1 scans, each at most 252 points
}

}  // namespace
}  // namespace eco::test
