#pragma once
/// @file transform_tree.hpp
/// The frames a recording's /tf and /tf_static describe, kept as tf2 keeps them: a tree in which
/// each frame has one parent, each link static or a timed track, and a transform between any two
/// frames of the tree at a time composed of the links between them, each interpolated (slerp)
/// at that time.
///
///   eco::io::TransformTree tf = bag.transform_tree();
///   std::optional<Eigen::Isometry3d> map_T_lidar = tf.lookup("map", "lidar", stamp);

#include <eco/io/pose_file.hpp>

#include <Eigen/Geometry>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace eco::io {

struct StampedTransform {
  double time = 0.0;  ///< [s]
  std::string parent, child;
  Eigen::Isometry3d parent_T_child = Eigen::Isometry3d::Identity();
};

class TransformTree {
 public:
  /// Adds a link's transform at a time (a static link's once: it holds at every time). Throws
  /// eco::io::Error naming `source` when the child already has another parent, or a link is given
  /// as both static and timed.
  void add(const StampedTransform& transform, bool is_static, const std::string& source);

  /// target_T_source at `time`: the pose of frame `source` in frame `target`. nullopt when a timed
  /// link between them has no transform on both sides of `time` (outside its span). Throws
  /// eco::io::Error when either frame is unknown or no chain of links joins them, naming the frames
  /// there are.
  [[nodiscard]] std::optional<Eigen::Isometry3d> lookup(const std::string& target, const std::string& source,
                                                       double time) const;
  /// The frames from `target` down to `source`: "map -> odom -> base_link -> lidar".
  [[nodiscard]] std::string chain(const std::string& target, const std::string& source) const;
  /// The topmost frame above `frame` (itself when it has no parent).
  [[nodiscard]] std::string root_of(const std::string& frame) const;
  [[nodiscard]] bool has_frame(const std::string& frame) const;
  [[nodiscard]] bool empty() const { return links_.empty(); }

 private:
  struct Link {
    std::string parent;
    bool is_static = false;
    PoseTrack track;  // one pose when static
  };
  [[nodiscard]] std::vector<std::string> ancestry(const std::string& frame) const;  // frame, its parent, ... root
  [[nodiscard]] std::optional<Eigen::Isometry3d> up_to(const std::string& ancestor, const std::string& frame,
                                                      double time) const;  // ancestor_T_frame

  std::map<std::string, Link> links_;  // by child frame
};

}  // namespace eco::io
