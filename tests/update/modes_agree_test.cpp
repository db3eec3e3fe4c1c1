// Exact and Quantised re-centring are two update strategies for one contract: fed the same
// stream, they hold the same points and answer every query the same after every frame.

#include "support/compare.hpp"
#include "support/streams.hpp"

namespace eco::test {
namespace {

using Params = std::tuple<InsertPolicy, Motion, Cloud>;
class ModesAgree : public ::testing::TestWithParam<Params> {};

TEST_P(ModesAgree, SameHeldSetAndAnswersEveryFrame) {
  const auto [policy, motion, cloud] = GetParam();
  Config quantised;
  quantised.insert_policy = policy;
  quantised.leaf_capacity = 4;
  Config exact = quantised;
  exact.recentring = Recentring::Exact;
  EgoOctree a(quantised), b(exact);
  Stream stream(motion, cloud, quantised.box_side, 7u);
  std::mt19937 rng(5);
  for (int t = 0; t < 120; ++t) {
    const Eigen::Isometry3d pose = stream.pose(t);
    const std::vector<Eigen::Vector3f> scan = stream.scan(t);
    const UpdateStats sa = a.update(pose, scan);
    const UpdateStats sb = b.update(pose, scan);
    SCOPED_TRACE("frame " + std::to_string(t));
    ASSERT_EQ(sa.inserted, sb.inserted);
    ASSERT_EQ(sa.pruned, sb.pruned);
    ASSERT_EQ(sorted(a.points()), sorted(b.points()));
    for (const Eigen::Vector3d& q : query_points(a, rng, 4)) {
      const std::vector<Neighbor> ka = a.knn(q, 8), kb = b.knn(q, 8);
      ASSERT_EQ(ka.size(), kb.size());
      for (std::size_t j = 0; j < ka.size(); ++j) ASSERT_EQ(ka[j].sq_dist, kb[j].sq_dist);
      std::vector<Eigen::Vector3d> ra, rb;
      for (const Neighbor& n : a.radius(q, 3.0)) ra.push_back(n.point);
      for (const Neighbor& n : b.radius(q, 3.0)) rb.push_back(n.point);
      ASSERT_EQ(sorted(ra), sorted(rb));
    }
    ASSERT_EQ(sorted_keys(a.voxel_keys(0.4)), sorted_keys(b.voxel_keys(0.4)));
  }
}

INSTANTIATE_TEST_SUITE_P(Streams, ModesAgree,
                         ::testing::Combine(::testing::Values(InsertPolicy::ShiftInOnly, InsertPolicy::AllInBox),
                                            ::testing::Values(Motion::Smooth, Motion::SubQuantum,
                                                              Motion::Diagonal, Motion::Teleport),
                                            ::testing::Values(Cloud::Surfaces, Cloud::Duplicates)));

}  // namespace
}  // namespace eco::test
