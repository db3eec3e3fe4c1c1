// Precision far from the origin: poses a million metres out, driving 3 km (so the precision
// origin moves at least once). Answers must agree with a double-precision brute force to within
// 1 mm, and with the float-storing oracle exactly. The sensor moves 2 m a frame (boxes overlap)
// and jumps 400 m every tenth frame.

#include "support/compare.hpp"
#include "support/streams.hpp"

#include <random>

namespace eco::test {
namespace {

class FarFromOrigin : public ::testing::TestWithParam<Recentring> {};

TEST_P(FarFromOrigin, AnswersAgreeWithDoubleBruteForceWithinOneMillimetre) {
  Config cfg;
  cfg.recentring = GetParam();
  cfg.insert_policy = InsertPolicy::AllInBox;
  EgoOctree tree(cfg);
  Oracle oracle(cfg);
  std::vector<Eigen::Vector3d> truth;  // double world points, the brute force
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-12.0, 12.0);
  const Eigen::Vector3d start(1.0e6, -2.0e6, 3.5e5);
  const double margin = 0.01;  // keep points 1 cm clear of the box walls: membership is not at stake
  constexpr int kFrames = 80;
  auto position = [&](int t) -> Eigen::Vector3d { return start + Eigen::Vector3d(2.0 * t + 400.0 * (t / 10), 0.3 * t, 0.05 * t); };
  // Within a float's rounding of a wall, the tree (stored floats) and the double brute force may
  // disagree: a point must stay clear of the walls of this frame's box and every later one.
  auto near_a_wall = [&](const Eigen::Vector3d& w, int from) {
    for (int t = from; t < kFrames; ++t) {
      if (((w - position(t)).cwiseAbs().array() - cfg.box_side / 2).abs().minCoeff() < margin) return true;
    }
    return false;
  };
  int rebases = 0;
  for (int t = 0; t < kFrames; ++t) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(0.1 * t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    pose.translation() = position(t);
    const Eigen::Vector3d c = pose.translation();
    auto inside = [&](const Eigen::Vector3d& w, double m) {
      return ((w - c).cwiseAbs().array() < cfg.box_side / 2 - m).all();
    };
    std::erase_if(truth, [&](const Eigen::Vector3d& w) { return !inside(w, 0.0); });
    std::vector<Eigen::Vector3f> scan;
    while (scan.size() < 600) {
      const Eigen::Vector3f s(float(u(rng)), float(u(rng)), float(u(rng)));
      const Eigen::Vector3d w = pose * s.cast<double>();
      if (near_a_wall(w, t)) continue;
      scan.push_back(s);
      if (inside(w, margin)) truth.push_back(w);
    }
    tree.update(pose, scan);
    oracle.update(pose, scan, tree.precision_origin());
    rebases += tree.last_update().rebased ? 1 : 0;
    ASSERT_LE((tree.precision_origin() - c).cwiseAbs().maxCoeff(), 2048.0);
    ASSERT_EQ(tree.size(), truth.size()) << "frame " << t;

    for (int i = 0; i < 20; ++i) {
      const Eigen::Vector3d q = i % 2 ? truth[std::size_t(rng()) % truth.size()]
                                      : Eigen::Vector3d(c + Eigen::Vector3d(u(rng), u(rng), u(rng)));
      std::vector<double> expected;
      for (const Eigen::Vector3d& w : truth) expected.push_back((w - q).norm());
      std::sort(expected.begin(), expected.end());
      const std::vector<Neighbor> got = tree.knn(q, 5);
      ASSERT_EQ(got.size(), 5u);
      for (std::size_t j = 0; j < got.size(); ++j) {
        ASSERT_NEAR(std::sqrt(got[j].sq_dist), expected[j], 1e-3) << "frame " << t;
        ASSERT_NEAR((got[j].point - q).norm(), expected[j], 1e-3);
      }
    }
    if (t % 10 == 0) {
      expect_same_answers(tree, oracle, rng, "frame " + std::to_string(t));
      if (HasFatalFailure()) return;
    }
  }
  EXPECT_GE(rebases, 1) << "the drive should have moved the precision origin";
}

INSTANTIATE_TEST_SUITE_P(Modes, FarFromOrigin, ::testing::Values(Recentring::Quantised, Recentring::Exact),
                         mode_name);

}  // namespace
}  // namespace eco::test
