// Per-point ids, intensities and times: stored with their point, carried through every structural
// operation (splits and collapses of small leaves, both re-centring modes, a precision-origin move
// and time-origin moves), aged in seconds, and returned by every query exactly as a brute force
// that keeps them in a flat list says.

#include "core/tree/tree.hpp"
#include "support/compare.hpp"
#include "support/rejected.hpp"
#include "support/streams.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>
#include <span>
#include <string>
#include <tuple>

namespace eco::test {
namespace {

enum class Age { None, Frames, Seconds };

constexpr double kStartTime = 1.7e9;   // a Unix time: far from the float range of offsets
constexpr double kFrameSeconds = 7.3;  // the time origin moves every ~9 frames
constexpr int kFrames = 30;

/// Frame 0 at the world origin, then a drive from x = 2030 m at 2 m a frame: the box jumps once
/// (farther than L), and the precision origin moves near frame 11 with points held.
Eigen::Isometry3d pose_at(int t) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(0.1 * t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  if (t > 0) pose.translation() = Eigen::Vector3d(2030.0 + 2.0 * (t - 1), 0.5 * t, 0.1 * t);
  return pose;
}

using Scan = AttributedScan;

/// Points in and around the box (some repeated, one not finite), ids unique over the stream,
/// times sweeping the frame's interval; every fifth frame a few points already 30 s old.
Scan make_scan(int t, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-12.0f, 12.0f);
  Scan s;
  constexpr int kPoints = 400;
  for (int i = 0; i < kPoints; ++i) {
    const Eigen::Vector3f p = i % 17 == 5 ? s.points.back() : Eigen::Vector3f(u(rng), u(rng), 0.3f * u(rng));
    s.points.push_back(i == 7 ? Eigen::Vector3f(NAN, 0.0f, 0.0f) : p);
    s.attributes.ids.push_back(std::uint32_t(t * 100000 + i));
    s.attributes.intensities.push_back(u(rng));
    const double swept = kStartTime + kFrameSeconds * (t + double(i) / kPoints);
    s.attributes.times.push_back(t % 5 == 4 && i % 40 == 0 ? swept - 30.0 : swept);
  }
  return s;
}

std::vector<std::uint32_t> sorted_ids(std::vector<std::uint32_t> ids) {
  std::sort(ids.begin(), ids.end());
  return ids;
}

/// Asserts that every query of `tree` returns the attributes the oracle holds for its points.
void expect_same_attributes(const EgoOctree& tree, const Oracle& oracle, std::mt19937& rng) {
  ASSERT_EQ(tree.check_invariants(), "");
  expect_same_held_attributes(tree, oracle);
  if (::testing::Test::HasFatalFailure()) return;
  const std::vector<HeldPoint> expected = oracle.points_with_attributes();
  std::map<std::uint32_t, HeldPoint> by_id;
  for (const HeldPoint& h : expected) by_id[h.attributes.id] = h;
  auto ids_where = [&](auto&& in) {
    std::vector<std::uint32_t> out;
    for (const HeldPoint& h : expected) {
      if (in(h.point)) out.push_back(h.attributes.id);
    }
    return sorted_ids(out);
  };
  for (const Eigen::Vector3d& q : query_points(tree, rng, 6)) {
    for (const std::size_t k : {1u, 8u, 40u}) {  // 40: beyond the results kept pending
      const std::vector<double> distances = oracle.knn_sq_dists(q, k);
      const std::vector<Neighbor> found = tree.knn(q, k);
      std::vector<std::uint32_t> ids(k);
      std::vector<double> sq_dists(k);
      const std::size_t n = tree.knn(q, ids, sq_dists);
      ASSERT_EQ(found.size(), distances.size());
      ASSERT_EQ(n, distances.size());
      for (std::size_t j = 0; j < n; ++j) {
        ASSERT_EQ(found[j].sq_dist, distances[j]);
        ASSERT_EQ(sq_dists[j], distances[j]);
        const HeldPoint& held = by_id.at(found[j].attributes.id);
        ASSERT_EQ(found[j].point, held.point);
        ASSERT_EQ(found[j].attributes, held.attributes);
        ASSERT_EQ(oracle.sq_dist_to_world(q, by_id.at(ids[j]).point), sq_dists[j]) << "id " << ids[j];
      }
    }
    const double r = 3.0;
    std::vector<std::uint32_t> in_radius;
    for (const Neighbor& nb : tree.radius(q, r)) {
      ASSERT_EQ(nb.attributes, by_id.at(nb.attributes.id).attributes);
      in_radius.push_back(nb.attributes.id);
    }
    ASSERT_EQ(sorted_ids(in_radius),
              ids_where([&](const Eigen::Vector3d& p) { return oracle.sq_dist_to_world(q, p) <= r * r; }));
    const Eigen::Vector3d lo = q - Eigen::Vector3d(2.0, 3.0, 1.0), hi = q + Eigen::Vector3d(4.0, 1.0, 2.0);
    std::vector<std::uint32_t> in_box;
    for (const HeldPoint& h : tree.box_with_attributes(lo, hi)) {
      ASSERT_EQ(h.attributes, by_id.at(h.attributes.id).attributes);
      ASSERT_EQ(h.point, by_id.at(h.attributes.id).point);
      in_box.push_back(h.attributes.id);
    }
    ASSERT_EQ(sorted_ids(in_box), ids_where([&](const Eigen::Vector3d& p) {
                return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
              }));
  }
}

using Params = std::tuple<Recentring, bool, Age>;

class AttributesOracle : public ::testing::TestWithParam<Params> {};

TEST_P(AttributesOracle, SurviveEveryStructuralOperationAndComeBackWithEveryQuery) {
  const auto [recentring, capped, age] = GetParam();
  Config cfg;
  cfg.recentring = recentring;
  cfg.leaf_capacity = 4;  // many splits, and collapses as points leave
  cfg.attributes = {true, true, true};
  if (capped) cfg.density_cap = {0.5, 2};
  if (age == Age::Frames) cfg.max_age_frames = 3;
  if (age == Age::Seconds) cfg.max_age_seconds = 20.0;
  EgoOctree tree(cfg);
  Oracle oracle(cfg);
  std::mt19937 rng(5);
  int rebases = 0, clock_moves = 0;
  std::size_t aged = 0, refused_as_old = 0;
  double time_origin = tree.time_origin();
  for (int t = 0; t < kFrames; ++t) {
    SCOPED_TRACE("frame " + std::to_string(t));
    const Scan scan = make_scan(t, rng);
    const UpdateStats& st = tree.update(pose_at(t), scan.view());
    oracle.update(pose_at(t), scan.points, tree.precision_origin(), scan.attributes, tree.time_origin());
    rebases += st.rebased ? 1 : 0;
    clock_moves += t > 0 && tree.time_origin() != time_origin ? 1 : 0;
    time_origin = tree.time_origin();
    aged += st.aged_out;
    refused_as_old += st.skipped_by_age;
    ASSERT_EQ(st.inserted + st.skipped_nonfinite + st.skipped_by_policy + st.skipped_by_density + st.skipped_by_age,
              scan.points.size())
        << "every scan point accounted for";
    expect_same_attributes(tree, oracle, rng);
    if (HasFatalFailure()) return;
    // a recent point's time comes back within half a float step at 128 s from the time origin
    for (const HeldPoint& h : tree.points_with_attributes()) {
      if (h.attributes.id / 100000 != std::uint32_t(t)) continue;
      const double given = scan.attributes.times[h.attributes.id % 100000];
      ASSERT_LE(std::abs(h.attributes.time - given), std::ldexp(128.0, -24)) << "id " << h.attributes.id;
    }
  }
  EXPECT_GE(rebases, 1) << "the precision origin never moved";
  EXPECT_GE(clock_moves, 1) << "the time origin never moved";
  if (age != Age::None) {
    EXPECT_GT(aged, 0u) << "nothing aged out";
  }
  EXPECT_EQ(refused_as_old > 0, age == Age::Seconds) << "the 30 s old scan points";
}

std::string param_name(const ::testing::TestParamInfo<Params>& info) {
  const auto [recentring, capped, age] = info.param;
  const char* ages[] = {"NoAge", "AgeInFrames", "AgeInSeconds"};
  return name(recentring) + (capped ? "_Capped_" : "_Uncapped_") + ages[int(age)];
}

INSTANTIATE_TEST_SUITE_P(Streams, AttributesOracle,
                         ::testing::Combine(::testing::Values(Recentring::Quantised, Recentring::Exact),
                                            ::testing::Bool(),
                                            ::testing::Values(Age::None, Age::Frames, Age::Seconds)),
                         param_name);

/// A scan of more new points than one insertion batch (Tree::kInsertChunk) goes in through several
/// batches: every point and its attributes are held as if in one.
TEST(AttributesOracleLargeScans, ScansLargerThanAnInsertionBatchAreHeldWhole) {
  Config cfg;
  cfg.attributes = {true, true, true};
  EgoOctree tree(cfg);
  Oracle oracle(cfg);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-9.9f, 9.9f);  // inside the box
  const std::size_t n = 2 * detail::Tree::kInsertChunk + 1234;
  for (int t = 0; t < 2; ++t) {
    SCOPED_TRACE("frame " + std::to_string(t));
    Scan scan;
    for (std::size_t i = 0; i < n; ++i) {
      scan.points.emplace_back(u(rng), u(rng), 0.5f * u(rng));
      scan.attributes.ids.push_back(std::uint32_t(t * n + i));
      scan.attributes.intensities.push_back(float(i % 251));
      scan.attributes.times.push_back(kStartTime + t + 1e-6 * double(i));
    }
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(0.05 * t, 0.0, 0.0);
    const UpdateStats st = tree.update(pose, scan.view());
    oracle.update(pose, scan.points, tree.precision_origin(), scan.attributes, tree.time_origin());
    EXPECT_GT(st.inserted, 2 * detail::Tree::kInsertChunk);
    expect_same_attributes(tree, oracle, rng);
    if (HasFatalFailure()) return;
  }
}

TEST(AttributesBadInput, MissingArraysAndBadTimesAreRejectedNamingThemAndTheTreeIsUnchanged) {
  Config cfg;
  cfg.attributes = {true, true, true};
  cfg.max_age_seconds = 20.0;
  EgoOctree tree(cfg);
  std::mt19937 rng(3);
  for (int t = 0; t < 3; ++t) {
    const Scan scan = make_scan(t, rng);
    tree.update(pose_at(t), scan.view());
  }
  std::vector<HeldPoint> before = tree.points_with_attributes();
  Oracle::sort_held(before);
  const double origin = tree.time_origin();
  auto expect_unchanged = [&] {
    std::vector<HeldPoint> now = tree.points_with_attributes();
    Oracle::sort_held(now);
    ASSERT_EQ(now.size(), before.size());
    for (std::size_t i = 0; i < now.size(); ++i) {
      ASSERT_EQ(now[i].point, before[i].point);
      ASSERT_EQ(now[i].attributes, before[i].attributes);
    }
    EXPECT_EQ(tree.frame_count(), 3u);
    EXPECT_EQ(tree.time_origin(), origin);
  };
  const Scan good = make_scan(3, rng);
  for (const char* missing : {"ids", "intensities", "times"}) {
    ScanView v = good.view();
    if (std::string(missing) == "ids") v.ids = nullptr;
    if (std::string(missing) == "intensities") v.intensities = nullptr;
    if (std::string(missing) == "times") v.times = nullptr;
    expect_rejected([&] { tree.update(pose_at(3), v); }, {std::string("scan.") + missing, "attributes."});
    expect_unchanged();
  }
  for (const double bad : {-1.0, -1e-300, double(NAN), double(INFINITY), -double(INFINITY)}) {
    Scan scan = good;
    scan.attributes.times[9] = bad;
    expect_rejected([&] { tree.update(pose_at(3), scan.view()); }, {"scan.times[9]", "finite and >= 0"});
    expect_unchanged();
  }
  std::vector<std::uint32_t> ids(4);
  std::vector<double> sq_dists(3);
  expect_rejected([&] { (void)tree.knn(Eigen::Vector3d::Zero(), ids, sq_dists); }, {"ids.size() = 4", "3"});
  expect_rejected([&] { (void)tree.knn(Eigen::Vector3d(NAN, 0, 0), ids, std::span<double>(sq_dists.data(), 4)); },
                  {"query"});
  // an empty scan needs no arrays
  EXPECT_NO_THROW(tree.update(pose_at(3), ScanView()));
}

TEST(AttributesBadInput, TheAgeInSecondsNeedsTimesAndOneUnit) {
  Config no_time;
  no_time.max_age_seconds = 5.0;
  expect_rejected([&] { EgoOctree t(no_time); }, {"max_age_seconds", "attributes.time"});
  Config both = no_time;
  both.attributes.time = true;
  both.max_age_frames = 4;
  expect_rejected([&] { EgoOctree t(both); }, {"max_age_seconds", "max_age_frames"});
  for (const double bad : {-1.0, double(NAN), double(INFINITY)}) {
    Config c;
    c.attributes.time = true;
    c.max_age_seconds = bad;
    expect_rejected([&] { EgoOctree t(c); }, {"max_age_seconds"});
  }
}

TEST(AttributesNotKept, ComeBackZeroAndGivenArraysAreIgnored) {
  Config cfg;
  cfg.attributes.intensity = true;  // only intensities
  EgoOctree tree(cfg);
  std::mt19937 rng(8);
  const Scan scan = make_scan(0, rng);
  tree.update(pose_at(0), scan.view());
  // by (x, y) of the sensor point (the pose is the identity); a repeated point has one per copy
  std::map<std::pair<float, float>, std::multiset<float>> intensities;
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    intensities[{scan.points[i].x(), scan.points[i].y()}].insert(scan.attributes.intensities[i]);
  }
  ASSERT_GT(tree.size(), 0u);
  for (const HeldPoint& h : tree.points_with_attributes()) {
    EXPECT_EQ(h.attributes.id, 0u);
    EXPECT_EQ(h.attributes.time, 0.0);
    std::multiset<float>& given = intensities.at({float(h.point.x()), float(h.point.y())});
    ASSERT_TRUE(given.contains(h.attributes.intensity)) << h.point.transpose();
    given.erase(given.find(h.attributes.intensity));
  }
  std::vector<std::uint32_t> ids(3);
  std::vector<double> sq_dists(3);
  expect_rejected([&] { (void)tree.knn(Eigen::Vector3d::Zero(), ids, sq_dists); }, {"attributes.ids"});
  // a tree keeping none leaves a reused buffer's attributes zero
  EgoOctree plain;
  plain.update(pose_at(0), scan.view());
  std::vector<Neighbor> found(5);
  for (Neighbor& n : found) n.attributes = {7u, 1.0f, 2.0};
  ASSERT_EQ(plain.knn(Eigen::Vector3d::Zero(), found), 5u);
  for (const Neighbor& n : found) EXPECT_EQ(n.attributes, PointAttributes{});
}

}  // namespace
}  // namespace eco::test
