// A wrong baseline is a wrong table: every benchmark method passes the oracle tests ECO passes —
// randomized streams, every motion pattern and insert policy, held set and every query equal to
// the brute force after every frame. `ioctree_global` keeps what left the box, so its oracle
// does not prune; `scan_only` keeps only the current scan's points in the box; `eco_clearing`
// clears free space whatever the config asks.

#include "support/compare.hpp"
#include "support/rejected.hpp"
#include "support/streams.hpp"

#include "baselines/method.hpp"

#include <tuple>

namespace eco::test {
namespace {

using baselines::make_method;
using baselines::Method;

/// Streams `frames` frames through method `name` and the oracle; every answer must agree after
/// every frame.
void stream_and_compare(const std::string& name, const Config& cfg, Stream stream, int frames) {
  const std::unique_ptr<Method> method = make_method(name, cfg);
  ASSERT_EQ(method->name(), name);
  const Memory memory = name == "ioctree_global" ? Memory::Everything
                        : name == "scan_only"    ? Memory::Nothing
                                                 : Memory::TheBox;
  Oracle oracle(method->config(), memory);  // the config the method runs: eco_clearing's clears
  std::mt19937 rng(17);
  for (int t = 0; t < frames; ++t) {
    const Eigen::Isometry3d pose = stream.pose(t);
    const std::vector<Eigen::Vector3f> scan = stream.scan(t);
    method->update(pose, scan);
    oracle.update(pose, scan, method->precision_origin());
    expect_same_world_answers(*method, oracle, rng, name + " frame " + std::to_string(t));
    if (::testing::Test::HasFatalFailure()) return;
  }
}

using Params = std::tuple<std::string, InsertPolicy, Motion, Cloud, bool>;

class BaselineOracle : public ::testing::TestWithParam<Params> {};

TEST_P(BaselineOracle, HeldSetAndQueriesMatchBruteForceEveryFrame) {
  const auto [name, policy, motion, cloud, small_leaves] = GetParam();
  Config cfg;
  cfg.insert_policy = policy;
  if (small_leaves) {  // deep trees: one point per leaf down to the minimum cell
    cfg.box_side = 7.5;
    cfg.leaf_capacity = 1;
    cfg.min_cell_size = 0.2;
  } else {
    cfg.leaf_capacity = 8;  // the paper's N_max
  }
  stream_and_compare(name, cfg, Stream(motion, cloud, cfg.box_side, 4321u), 24);
}

std::string param_name(const ::testing::TestParamInfo<Params>& info) {
  const auto [name, policy, motion, cloud, small_leaves] = info.param;
  return name + (policy == InsertPolicy::ShiftInOnly ? "_ShiftIn_" : "_AllInBox_") + test::name(motion) + "_" +
         test::name(cloud) + (small_leaves ? "_OnePointLeaves" : "");
}

/// Every method that holds the cube (eco_ball and eco_box: EcoBallAndEcoBoxHoldTheirRegionExactly).
std::vector<std::string> cube_methods() {
  std::vector<std::string> names = baselines::method_names();
  std::erase_if(names, [](const std::string& n) { return n == "eco_ball" || n == "eco_box"; });
  return names;
}

INSTANTIATE_TEST_SUITE_P(
    Methods, BaselineOracle,
    ::testing::Combine(::testing::ValuesIn(cube_methods()),
                       ::testing::Values(InsertPolicy::ShiftInOnly, InsertPolicy::AllInBox),
                       ::testing::Values(Motion::Smooth, Motion::Still, Motion::Backwards, Motion::Diagonal,
                                         Motion::Teleport),
                       ::testing::Values(Cloud::Surfaces, Cloud::Duplicates), ::testing::Bool()),
    param_name);

using CappedParams = std::tuple<std::string, InsertPolicy, Motion>;

class BaselineCapped : public ::testing::TestWithParam<CappedParams> {};

TEST_P(BaselineCapped, DensityCapAndAgeLimitAsTheContractSays) {
  const auto [name, policy, motion] = GetParam();
  Config cfg;
  cfg.insert_policy = policy;
  cfg.density_cap = {0.5, 2};
  // a global map never deletes; a map of the current scan has nothing to age
  cfg.max_age_frames = name == "ioctree_global" || name == "scan_only" ? 0 : 4;
  stream_and_compare(name, cfg, Stream(motion, Cloud::Duplicates, cfg.box_side, 99u), 16);
}

std::string capped_name(const ::testing::TestParamInfo<CappedParams>& info) {
  const auto [name, policy, motion] = info.param;
  return name + (policy == InsertPolicy::ShiftInOnly ? "_ShiftIn_" : "_AllInBox_") + test::name(motion);
}

INSTANTIATE_TEST_SUITE_P(
    OctreeMethods, BaselineCapped,
    ::testing::Combine(::testing::Values("eco", "eco_exact", "eco_clearing", "octree_base", "ioctree_global",
                                           "ioctree_target", "scan_only"),
                       ::testing::Values(InsertPolicy::ShiftInOnly, InsertPolicy::AllInBox),
                       ::testing::Values(Motion::Smooth, Motion::Still, Motion::Teleport)),
    capped_name);

/// The octrees clear free space as ECO does (the same stage); scan_only has nothing to clear.
class BaselineClearing : public ::testing::TestWithParam<CappedParams> {};

TEST_P(BaselineClearing, FreeSpaceClearingAsTheContractSays) {
  const auto [name, policy, motion] = GetParam();
  Config cfg;
  cfg.insert_policy = policy;
  cfg.clearing.enabled = true;
  cfg.clearing.margin = 0.1;
  cfg.sensor = {-60.0, 60.0, 4.0, 4.0, 30.0};  // coarse pixels over the streams' scattered scans
  if (name == "scan_only") cfg.clearing.enabled = false;
  for (const bool arrivals : {false, true}) {
    SCOPED_TRACE(arrivals ? "clearing.arrivals on" : "clearing.arrivals off");
    cfg.clearing.arrivals = arrivals;
    stream_and_compare(name, cfg, Stream(motion, Cloud::Surfaces, cfg.box_side, 7u), 12);
  }
}

INSTANTIATE_TEST_SUITE_P(
    OctreeMethods, BaselineClearing,
    ::testing::Combine(::testing::Values("eco", "eco_exact", "eco_clearing", "octree_base", "ioctree_global",
                                         "ioctree_target", "scan_only"),
                       ::testing::Values(InsertPolicy::ShiftInOnly, InsertPolicy::AllInBox),
                       ::testing::Values(Motion::Smooth, Motion::Still, Motion::Teleport)),
    capped_name);

/// The flat baselines honour the density cap as the octrees do (a set of occupied cells kept as
/// points come and go) but have no age limit.
class FlatCapped : public ::testing::TestWithParam<CappedParams> {};

TEST_P(FlatCapped, DensityCapAsTheContractSays) {
  const auto [name, policy, motion] = GetParam();
  Config cfg;
  cfg.insert_policy = policy;
  cfg.density_cap = {0.5, 2};
  stream_and_compare(name, cfg, Stream(motion, Cloud::Duplicates, cfg.box_side, 99u), 16);
}

INSTANTIATE_TEST_SUITE_P(FlatMethods, FlatCapped,
                         ::testing::Combine(::testing::Values("nanoflann", "pcl_octree"),
                                            ::testing::Values(InsertPolicy::ShiftInOnly, InsertPolicy::AllInBox),
                                            ::testing::Values(Motion::Smooth, Motion::Still, Motion::Teleport)),
                         capped_name);

TEST(Baselines, UnknownNameAndUnsupportedConfigAreRejectedByName) {
  try {
    (void)make_method("kdtree", Config{});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'kdtree'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("octree_base"), std::string::npos) << e.what();
  }
  // what the flat baselines do not have, refused by the field that asks for it
  Config aged;
  aged.max_age_frames = 3;
  Config clearing;
  clearing.clearing.enabled = true;
  Config attributed;
  attributed.attributes.ids = true;
  for (const auto& [unsupported, words] : {std::pair(aged, "max_age_frames = 3"), std::pair(clearing, "clearing.enabled = true"),
                                           std::pair(attributed, "attributes.ids")}) {
    const Config& config = unsupported;  // a structured binding is not captured by clang 14's lambdas
    for (const char* flat : {"nanoflann", "pcl_octree", "scan_pass"}) {
      SCOPED_TRACE(flat);
      test::expect_rejected([&] { (void)make_method(flat, config); }, {words});
    }
  }
  Config bad;
  bad.box_side = -1.0;
  for (const std::string& name : baselines::method_names()) {
    EXPECT_THROW((void)make_method(name, bad), std::invalid_argument) << name;
  }
}

TEST(Baselines, EcoBallAndEcoBoxHoldTheirRegionExactly) {
  Config cfg;
  cfg.insert_policy = InsertPolicy::AllInBox;
  cfg.leaf_capacity = 8;
  for (const char* name : {"eco_ball", "eco_box"}) {
    for (const Motion motion : {Motion::Smooth, Motion::Teleport}) {
      SCOPED_TRACE(std::string(name) + " " + test::name(motion));
      const std::unique_ptr<Method> method = make_method(name, cfg);
      EXPECT_EQ(method->config().region.shape,
                std::string(name) == "eco_ball" ? RegionShape::Ball : RegionShape::OrientedBox);
      EXPECT_LE(method->config().region.reach(), cfg.box_side / 2);
      stream_and_compare(name, cfg, Stream(motion, Cloud::Uniform, cfg.box_side, 99u), 16);
      if (HasFatalFailure()) return;
    }
  }
}

TEST(Baselines, TheOthersRefuseARegionTheyCannotHold) {
  Config ball;
  ball.insert_policy = InsertPolicy::AllInBox;
  ball.region = {RegionShape::Ball, 6.0};
  for (const std::string& name : baselines::method_names()) {
    SCOPED_TRACE(name);
    if (name.rfind("eco", 0) == 0 || name == "scan_only") {  // ECO holds it; the scan is the Chamfer reference
      EXPECT_NO_THROW((void)make_method(name, ball));
      continue;
    }
    test::expect_rejected([&] { (void)make_method(name, ball); }, {"'" + name + "' holds the cube only", "region.shape = ball"});
  }
}

TEST(Baselines, RejectedUpdateLeavesTheMethodUnchanged) {
  for (const std::string& name : baselines::method_names()) {
    SCOPED_TRACE(name);
    const std::unique_ptr<Method> method = make_method(name, Config{});
    const std::vector<Eigen::Vector3f> scan{{1, 2, 0.5f}, {-3, 1, 0}};
    method->update(Eigen::Isometry3d::Identity(), scan);
    Eigen::Isometry3d bad = Eigen::Isometry3d::Identity();
    bad.translation().x() = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(method->update(bad, scan), std::invalid_argument);
    bad = Eigen::Isometry3d::Identity();
    bad.linear()(0, 0) = 2.0;
    EXPECT_THROW(method->update(bad, scan), std::invalid_argument);
    EXPECT_EQ(method->size(), 2u);
    EXPECT_EQ(method->check_invariants(), "");
  }
}

TEST(Baselines, RadiusIncludesPointsExactlyOnTheSphere) {
  for (const std::string& name : baselines::method_names()) {
    SCOPED_TRACE(name);
    const std::unique_ptr<Method> method = make_method(name, Config{});
    const std::vector<Eigen::Vector3f> scan{{1, 0, 0}, {0, -2, 0}, {0, 0, 0.5f}};
    method->update(Eigen::Isometry3d::Identity(), scan);
    EXPECT_EQ(method->radius(Eigen::Vector3d::Zero(), 1.0).size(), 2u);  // |p| = 1 is inside
    EXPECT_EQ(method->radius(Eigen::Vector3d::Zero(), 2.0).size(), 3u);
    EXPECT_EQ(method->radius(Eigen::Vector3d::Zero(), 0.5).size(), 1u);
  }
}

TEST(Baselines, EcoClearingClearsWhatEcoKeepsWhateverTheConfigSays) {
  // A wall 10 m ahead, dense enough to fill every pixel around the ray through (5, 0, 0); a point
  // there in the first frame only: the second frame's wall shows it was free space.
  std::vector<Eigen::Vector3f> wall;
  for (int i = -50; i <= 50; ++i) {
    for (int j = -50; j <= 50; ++j) wall.emplace_back(9.5f, 0.02f * float(i), 0.02f * float(j));
  }
  std::vector<Eigen::Vector3f> first = wall;
  first.emplace_back(5.0f, 0.0f, 0.0f);
  Config config;  // clearing off, as by default
  const std::unique_ptr<Method> eco = make_method("eco", config), clearing = make_method("eco_clearing", config);
  EXPECT_TRUE(clearing->config().clearing.enabled);
  EXPECT_EQ(clearing->config().clearing.margin, config.clearing.margin);
  for (Method* method : {eco.get(), clearing.get()}) {
    method->update(Eigen::Isometry3d::Identity(), first);
    method->update(Eigen::Isometry3d::Identity(), wall);
  }
  EXPECT_EQ(eco->size(), 2 * wall.size() + 1);  // AllInBox: the wall twice
  EXPECT_EQ(clearing->size(), 2 * wall.size());
  EXPECT_EQ(eco->radius(Eigen::Vector3d(5, 0, 0), 0.1).size(), 1u);
  EXPECT_EQ(clearing->radius(Eigen::Vector3d(5, 0, 0), 0.1).size(), 0u);
}

TEST(Baselines, GlobalOctreeDeepensAsTheRobotDrivesAwayEcoDoesNot) {
  Config cfg;
  cfg.leaf_capacity = 8;
  const std::unique_ptr<Method> eco = make_method("eco", cfg);
  const std::unique_ptr<Method> target = make_method("ioctree_target", cfg);
  Stream stream(Motion::Smooth, Cloud::Surfaces, cfg.box_side, 5u);
  Stats eco_first, target_first;
  for (int t = 0; t < 400; t += 1) {
    Eigen::Isometry3d pose = stream.pose(t);
    pose.translation().x() *= 3.0;  // 2.7 m a frame: over a kilometre in 400 frames
    const std::vector<Eigen::Vector3f> scan = stream.scan(t);
    eco->update(pose, scan);
    target->update(pose, scan);
    if (t == 0) {
      eco_first = eco->stats();
      target_first = target->stats();
    }
  }
  ASSERT_EQ(sorted(eco->points()), sorted(target->points()));
  EXPECT_NEAR(eco->stats().mean_leaf_depth, eco_first.mean_leaf_depth, 1.0);
  EXPECT_GE(target->stats().mean_leaf_depth, target_first.mean_leaf_depth + 5.0)
      << "the global root should have doubled at least five times";
}

}  // namespace
}  // namespace eco::test
