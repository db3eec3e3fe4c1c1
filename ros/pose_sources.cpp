#include "pose_sources.hpp"

#include "ros_messages.hpp"

#include <algorithm>
#include <memory>

namespace eco::ros_node {
namespace {

/// target_T_source at `time` from tf, or nullopt.
std::optional<Eigen::Isometry3d> tf_lookup(const tf2_ros::Buffer& buffer, const std::string& target,
                                           const std::string& source, double time) {
  try {
    return pose_of(buffer.lookupTransform(target, source, ros::Time(time)).transform);
  } catch (const tf2::TransformException&) {
    return std::nullopt;
  }
}

/// Whether tf joins `target` and `source` at both ends of [first, last]; `why` says what is missing.
bool tf_reaches(const tf2_ros::Buffer& buffer, const std::string& target, const std::string& source, double first,
                double last, std::string& why) {
  return buffer.canTransform(target, source, ros::Time(first), &why) &&
         buffer.canTransform(target, source, ros::Time(last), &why);
}

}  // namespace

SweepPoses TfPoses::sweep(const std::string& frame_id, double first, double last) {
  SweepPoses out;
  if (!tf_reaches(buffer_, fixed_frame_, frame_id, first, last, out.why)) return out;
  out.state = SweepPoses::State::Ready;
  out.pose_at = [&buffer = buffer_, fixed = fixed_frame_, frame_id](double t) { return tf_lookup(buffer, fixed, frame_id, t); };
  return out;
}

void TopicPoses::add(const nav_msgs::Odometry& pose) {
  if (track_.poses.empty()) {
    frame_id_ = pose.header.frame_id;
    child_frame_id_ = pose.child_frame_id;
  }
  const geometry_msgs::Pose& p = pose.pose.pose;
  const double time = seconds_of(std::int64_t(pose.header.stamp.toNSec()));
  // in stamp order, a pose of the same stamp after those there (as a recording's are sorted)
  const auto at = std::upper_bound(track_.times.begin(), track_.times.end(), time);
  const auto i = at - track_.times.begin();
  track_.times.insert(at, time);
  track_.poses.insert(track_.poses.begin() + i,
                      io::pose_of({p.position.x, p.position.y, p.position.z},
                                  Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z)));
}

SweepPoses TopicPoses::sweep(const std::string& frame_id, double first, double last) {
  SweepPoses out;
  if (track_.poses.empty()) {
    out.why = "no pose on " + topic_ + " yet";
    return out;
  }
  if (first < track_.times.front()) {
    out.state = SweepPoses::State::Never;
    out.why = "the cloud is older than the first pose on " + topic_;
    return out;
  }
  if (last > track_.times.back()) {
    out.why = "no pose on " + topic_ + " after the sweep's end yet";
    return out;
  }
  // a copy of the poses the sweep needs: the track goes on changing while the cloud is placed
  const auto from = std::upper_bound(track_.times.begin(), track_.times.end(), first) - track_.times.begin();
  const auto to = std::lower_bound(track_.times.begin(), track_.times.end(), last) - track_.times.begin();
  auto needed = std::make_shared<io::PoseTrack>();
  const auto lo = std::max<std::ptrdiff_t>(from - 1, 0);
  const auto hi = std::min<std::ptrdiff_t>(to + 1, std::ptrdiff_t(track_.times.size()));
  needed->times.assign(track_.times.begin() + lo, track_.times.begin() + hi);
  needed->poses.assign(track_.poses.begin() + lo, track_.poses.begin() + hi);
  if (child_frame_id_.empty() || child_frame_id_ == frame_id) {
    out.state = SweepPoses::State::Ready;
    out.pose_at = [needed](double t) { return io::pose_at(*needed, t); };
    return out;
  }
  if (!tf_reaches(buffer_, child_frame_id_, frame_id, first, last, out.why)) return out;
  out.state = SweepPoses::State::Ready;
  out.pose_at = [needed, &buffer = buffer_, child = child_frame_id_, frame_id](double t) -> std::optional<Eigen::Isometry3d> {
    const std::optional<Eigen::Isometry3d> pose = io::pose_at(*needed, t);
    const std::optional<Eigen::Isometry3d> extrinsic = tf_lookup(buffer, child, frame_id, t);
    if (!pose || !extrinsic) return std::nullopt;
    return *pose * *extrinsic;
  };
  return out;
}

void TopicPoses::forget_before(double time) {
  // keep the last pose before `time`: a sweep from `time` on interpolates from it
  const auto keep_from = std::upper_bound(track_.times.begin(), track_.times.end(), time) - track_.times.begin() - 1;
  if (keep_from <= 0) return;
  track_.times.erase(track_.times.begin(), track_.times.begin() + keep_from);
  track_.poses.erase(track_.poses.begin(), track_.poses.begin() + keep_from);
}

std::string TopicPoses::describe() const {
  return topic_ + (track_.poses.empty() ? "" : " (" + child_frame_id_ + " in " + frame_id_ + ")");
}

}  // namespace eco::ros_node
