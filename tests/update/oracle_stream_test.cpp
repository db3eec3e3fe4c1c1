// Oracle on a live set: randomized streams through every re-centring mode, insert policy,
// motion pattern, point distribution and several (L, N_max, k); after every frame the held set
// and every query must equal the brute force exactly.

#include "support/compare.hpp"
#include "support/streams.hpp"

#include <tuple>

namespace eco::test {
namespace {

struct Shape {
  double box_side;
  std::uint32_t leaf_capacity;
  double min_cell_size;
  std::uint32_t quantum_levels;
};

const Shape kShapes[] = {
    {20.0, 8, 0.05, 3},  // the paper's L and N_max
    {7.5, 1, 0.2, 2},    // one point per leaf: splits down to the minimum cell
    {50.0, 32, 0.1, 4},
    {20.0, 128, 0.1, 3},  // the library's defaults
};

using Params = std::tuple<Recentring, InsertPolicy, Motion, Cloud, int>;

class OracleStream : public ::testing::TestWithParam<Params> {};

TEST_P(OracleStream, HeldSetAndQueriesMatchBruteForceEveryFrame) {
  const auto [recentring, policy, motion, cloud, shape_index] = GetParam();
  const Shape& shape = kShapes[shape_index];
  Config cfg;
  cfg.box_side = shape.box_side;
  cfg.leaf_capacity = shape.leaf_capacity;
  cfg.min_cell_size = shape.min_cell_size;
  cfg.quantum_levels = shape.quantum_levels;
  cfg.recentring = recentring;
  cfg.insert_policy = policy;

  EgoOctree tree(cfg);
  Oracle oracle(cfg);
  Stream stream(motion, cloud, cfg.box_side, 1234u + unsigned(shape_index));
  std::mt19937 rng(99);
  for (int t = 0; t < 30; ++t) {
    const Eigen::Isometry3d pose = stream.pose(t);
    const std::vector<Eigen::Vector3f> scan = stream.scan(t);
    const UpdateStats& st = tree.update(pose, scan);
    oracle.update(pose, scan, tree.precision_origin());
    ASSERT_EQ(st.scan_points, scan.size());
    ASSERT_EQ(st.inserted + st.skipped_nonfinite + st.skipped_by_policy + st.skipped_by_density,
              scan.size());
    expect_same_answers(tree, oracle, rng, "frame " + std::to_string(t));
    if (HasFatalFailure()) return;
  }
}

std::string param_name(const ::testing::TestParamInfo<Params>& info) {
  const auto [recentring, policy, motion, cloud, shape] = info.param;
  return name(recentring) + (policy == InsertPolicy::ShiftInOnly ? "_ShiftIn_" : "_AllInBox_") + name(motion) + "_" +
         name(cloud) + "_Shape" + std::to_string(shape);
}

INSTANTIATE_TEST_SUITE_P(
    Streams, OracleStream,
    ::testing::Combine(::testing::Values(Recentring::Quantised, Recentring::Exact),
                       ::testing::Values(InsertPolicy::ShiftInOnly, InsertPolicy::AllInBox),
                       ::testing::Values(Motion::Smooth, Motion::Still, Motion::SubQuantum,
                                         Motion::Backwards, Motion::Diagonal, Motion::Teleport),
                       ::testing::Values(Cloud::Uniform, Cloud::Surfaces, Cloud::Duplicates, Cloud::Few),
                       ::testing::Range(0, int(std::size(kShapes)))),
    param_name);

}  // namespace
}  // namespace eco::test
