// A map that shrinks gives its memory back: after dense frames, the sensor drives on into sparse
// ones, most held points leave, and the update's last step moves the leaves' blocks to the pools'
// front, a megabyte an update (src/core/tree/tree.hpp, give_back_memory). Every frame the held set,
// every query and every point's attributes equal the brute force's; the bytes follow the map down.

#include "support/compare.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>

namespace eco::test {
namespace {

using Scan = AttributedScan;

/// `n` points spread through the box around the sensor (sensor frame), with ids unique over
/// the stream, intensities and the frame's time.
Scan make_scan(int t, std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-9.9f, 9.9f);
  Scan s;
  for (std::size_t i = 0; i < n; ++i) {
    s.points.emplace_back(u(rng), u(rng), 0.3f * u(rng));
    s.attributes.ids.push_back(std::uint32_t(t) << 20 | std::uint32_t(i));
    s.attributes.intensities.push_back(float(i % 97));
    s.attributes.times.push_back(100.0 + 0.1 * t);
  }
  return s;
}

TEST(MemoryReturn, AMapThatShrinksGivesBackWhatItHeldAndLosesNothing) {
  for (const Recentring recentring : {Recentring::Quantised, Recentring::Exact}) {
    SCOPED_TRACE(recentring == Recentring::Exact ? "Exact" : "Quantised");
    Config cfg;
    cfg.recentring = recentring;
    cfg.attributes = {true, true, true};
    EgoOctree tree(cfg);
    Oracle oracle(cfg);
    std::mt19937 rng(21);
    std::size_t peak = 0;
    for (int t = 0; t < 10; ++t) {
      SCOPED_TRACE("frame " + std::to_string(t));
      // two dense frames in place, then 5 m a frame into sparse ones, out of the dense ones by frame 5 (a megabyte of blocks moves per update)
      const Scan scan = make_scan(t, t < 2 ? 90000 : 1500, rng);
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.translation() = Eigen::Vector3d(t < 2 ? 0.0 : 5.0 * (t - 1), 0.3 * t, 0.0);
      tree.update(pose, scan.view());
      oracle.update(pose, scan.points, tree.precision_origin(), scan.attributes, tree.time_origin());
      expect_same_answers(tree, oracle, rng, "");
      if (HasFatalFailure()) return;
      expect_same_held_attributes(tree, oracle);
      if (HasFatalFailure()) return;
      peak = std::max(peak, tree.stats().bytes);
    }
    ASSERT_LT(tree.size(), 10000u);
    // without giving back, the point pools would keep the dense frames' ~7 MB (node slots keep
    // their peak)
    EXPECT_LT(tree.stats().bytes, peak / 3) << "peak " << peak << " B, now " << tree.size() << " points";
  }
}

}  // namespace
}  // namespace eco::test
