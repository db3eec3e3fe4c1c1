// tf's tree of frames: a transform between any two frames, looked up at a time, against the
// product of every link from the root taken one by one (the brute force); timed links
// interpolated and absent outside their span; a second parent, a link both static and timed, and
// frames no chain joins refused by name, the tree unchanged.

#include <eco/io/error.hpp>
#include <eco/io/transform_tree.hpp>

#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <random>
#include <string>

namespace eco::io {
namespace {

Eigen::Isometry3d random_pose(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
  pose.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng));
  return pose;
}

/// map -> odom -> base_link -> lidar, base_link -> camera, map -> tag: odom -> base_link and
/// map -> tag timed (poses at 10.0 and 10.5 s), the others static.
struct Frames {
  TransformTree tree;
  std::map<std::string, std::string> parent;
  std::map<std::string, PoseTrack> link;  // by child; one pose when static

  explicit Frames(unsigned seed) {
    std::mt19937 rng(seed);
    const auto add = [&](const std::string& p, const std::string& c, bool timed) {
      parent[c] = p;
      for (const double t : timed ? std::vector<double>{10.5, 10.0} : std::vector<double>{0.0}) {  // out of order
        const Eigen::Isometry3d pose = random_pose(rng);
        tree.add({t, p, c, pose}, !timed, "test");
        if (timed) {
          link[c].times.insert(link[c].times.begin() + (t > 10.2 ? link[c].times.size() : 0), t);
          link[c].poses.insert(link[c].poses.begin() + (t > 10.2 ? link[c].poses.size() : 0), pose);
        } else {
          link[c].poses = {pose};
        }
      }
    };
    add("map", "odom", false);
    add("odom", "base_link", true);
    add("base_link", "lidar", false);
    add("base_link", "camera", false);
    add("map", "tag", true);
  }

  /// map_T_frame, link by link from the frame up.
  std::optional<Eigen::Isometry3d> from_map(std::string frame, double t) const {
    Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
    while (frame != "map") {
      const PoseTrack& track = link.at(frame);
      const std::optional<Eigen::Isometry3d> step = track.timed() ? pose_at(track, t) : track.poses.front();
      if (!step) return std::nullopt;
      out = *step * out;
      frame = parent.at(frame);
    }
    return out;
  }
};

TEST(TransformTree, EveryPairOfFramesIsTheProductOfItsLinks) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Frames frames(seed);
    const std::vector<std::string> names{"map", "odom", "base_link", "lidar", "camera", "tag"};
    for (const double t : {10.0, 10.2, 10.37, 10.5}) {
      for (const std::string& target : names) {
        for (const std::string& source : names) {
          const std::optional<Eigen::Isometry3d> got = frames.tree.lookup(target, source, t);
          const std::optional<Eigen::Isometry3d> map_T_target = frames.from_map(target, t), map_T_source = frames.from_map(source, t);
          ASSERT_TRUE(got && map_T_target && map_T_source) << target << " " << source << " " << t;
          const Eigen::Isometry3d want = map_T_target->inverse() * *map_T_source;
          EXPECT_LT((got->matrix() - want.matrix()).cwiseAbs().maxCoeff(), 1e-12) << target << " <- " << source << " at " << t;
        }
      }
    }
  }
}

TEST(TransformTree, ATimedLinkReachesOnlyItsSpan) {
  const Frames frames(7);
  EXPECT_FALSE(frames.tree.lookup("map", "lidar", 9.99));
  EXPECT_FALSE(frames.tree.lookup("odom", "base_link", 10.51));
  // static links alone hold at any time, and a pair whose chain has no timed link
  EXPECT_TRUE(frames.tree.lookup("base_link", "camera", 99.0));
  EXPECT_TRUE(frames.tree.lookup("lidar", "camera", -5.0));
  EXPECT_TRUE(frames.tree.lookup("lidar", "lidar", -5.0));
}

TEST(TransformTree, ChainsAndRootsAreNamed) {
  const Frames frames(3);
  EXPECT_EQ(frames.tree.chain("map", "lidar"), "map -> odom -> base_link -> lidar");
  EXPECT_EQ(frames.tree.chain("camera", "lidar"), "camera <- base_link -> lidar");
  EXPECT_EQ(frames.tree.root_of("camera"), "map");
  EXPECT_EQ(frames.tree.root_of("map"), "map");
  EXPECT_TRUE(frames.tree.has_frame("map"));
  EXPECT_FALSE(frames.tree.has_frame("gps"));
}

std::string refusal(const std::function<void()>& call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  return "(taken)";
}

TEST(TransformTree, WhatBreaksTheTreeIsRefusedByNameAndChangesNothing) {
  Frames frames(11);
  const Eigen::Isometry3d before = *frames.tree.lookup("map", "lidar", 10.25);
  const std::string second_parent = refusal([&] { frames.tree.add({10.1, "map", "lidar", {}}, true, "bag, /tf_static message 3"); });
  EXPECT_NE(second_parent.find("bag, /tf_static message 3: frame lidar is given two parents, base_link and map"), std::string::npos)
      << second_parent;
  const std::string both = refusal([&] { frames.tree.add({10.1, "odom", "base_link", {}}, true, "bag"); });
  EXPECT_NE(both.find("the link odom -> base_link is both static and timed"), std::string::npos) << both;
  EXPECT_NE(refusal([&] { frames.tree.add({10.1, "lidar", "lidar", {}}, false, "bag"); }).find("links no two frames"), std::string::npos);
  EXPECT_NE(refusal([&] { frames.tree.add({10.1, "", "lidar", {}}, false, "bag"); }).find("links no two frames"), std::string::npos);
  EXPECT_EQ(frames.tree.lookup("map", "lidar", 10.25)->matrix(), before.matrix());

  frames.tree.add({0.0, "gps_origin", "gps", {}}, true, "bag");  // a second tree
  const std::string apart = refusal([&] { (void)frames.tree.lookup("map", "gps", 10.25); });
  EXPECT_NE(apart.find("no chain of transforms joins map and gps; the frames are: base_link, camera, gps, gps_origin, lidar, "
                       "map, odom, tag"),
            std::string::npos)
      << apart;
  EXPECT_NE(refusal([&] { (void)frames.tree.lookup("map", "velodyne", 10.25); }).find("joins map and velodyne"), std::string::npos);
}

}  // namespace
}  // namespace eco::io
