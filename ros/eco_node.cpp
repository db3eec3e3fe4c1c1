#include "eco_node.hpp"

#include "ros_messages.hpp"

#include <geometry_msgs/TransformStamped.h>

#include <algorithm>

namespace eco::ros_node {
namespace {

double ms_since(Clock::time_point from) {
  return std::chrono::duration<double, std::milli>(Clock::now() - from).count();
}

ros::Time ros_time(std::int64_t nanoseconds) {
  ros::Time t;
  t.fromNSec(std::uint64_t(nanoseconds));
  return t;
}

}  // namespace

EcoNode::EcoNode(ros::NodeHandle& node, ros::NodeHandle& private_node, std::unique_ptr<MapSession> session)
    : session_(std::move(session)),
      settings_(session_->settings()),
      tf_listener_(tf_buffer_, node),
      publisher_(private_node, settings_) {
  clouds_ = node.subscribe(settings_.cloud_topic, std::uint32_t(settings_.queue_size), &EcoNode::on_cloud, this);
  save_ = private_node.advertiseService("save", &EcoNode::on_save, this);
  if (settings_.odometry) {
    odom_ = private_node.advertise<nav_msgs::Odometry>("odom", 100);
    ROS_INFO("eco_node: mapping %s, poses estimated by ECO's odometry (published on %s and as tf %s -> the clouds' "
             "frame)", clouds_.getTopic().c_str(), odom_.getTopic().c_str(), settings_.fixed_frame.c_str());
    return;
  }
  if (settings_.pose_topic.empty()) {
    poses_ = std::make_unique<TfPoses>(tf_buffer_, settings_.fixed_frame);
  } else {
    auto topic = std::make_unique<TopicPoses>(tf_buffer_, node.resolveName(settings_.pose_topic));
    topic_poses_ = topic.get();
    poses_ = std::move(topic);
    pose_messages_ = node.subscribe(settings_.pose_topic, 1000, &EcoNode::on_pose, this);
  }
  // started while a cloud waits (tf has no callback of its own when a transform arrives)
  retry_ = node.createSteadyTimer(ros::WallDuration(std::min(0.005, settings_.tf_timeout / 4)),
                                  [this](const ros::SteadyTimerEvent&) { take_ready(); }, false, false);
  ROS_INFO("eco_node: mapping %s, placed by %s", clouds_.getTopic().c_str(), poses_->describe().c_str());
}

void EcoNode::on_cloud(const sensor_msgs::PointCloud2::ConstPtr& msg) {
  const Clock::time_point received = Clock::now();
  const std::uint32_t seq = msg->header.seq;
  if (last_seq_ && seq > *last_seq_ + 1) {
    lost_ += seq - *last_seq_ - 1;
    ROS_WARN_THROTTLE(1.0, "eco_node: %u clouds on %s never reached the node before seq %u (%zu so far): a queue "
                      "upstream or this subscriber's (~queue_size %d) overflowed",
                      seq - *last_seq_ - 1, clouds_.getTopic().c_str(), seq, lost_, settings_.queue_size);
  }
  last_seq_ = seq;
  Waiting cloud{{}, received};
  try {
    const bool first = session_->layout().empty();
    cloud.sweep = session_->decode(cloud_bytes(*msg), clouds_.getTopic() + " seq " + std::to_string(seq));
    if (first) ROS_INFO("eco_node: clouds read as %s", session_->layout().c_str());
  } catch (const std::exception& e) {
    ++refused_;
    ROS_ERROR_THROTTLE(1.0, "eco_node: cloud not taken (%zu so far): %s", refused_, e.what());
    return;
  }
  if (settings_.odometry) {
    take_by_odometry(std::move(cloud));
    return;
  }
  waiting_.push_back(std::move(cloud));
  take_ready();
}

void EcoNode::on_pose(const nav_msgs::Odometry::ConstPtr& msg) {
  topic_poses_->add(*msg);
  take_ready();
}

SweepPoses EcoNode::poses_after_waiting(const DecodedSweep& sweep) {
  // the sweep as far as the poses reach (a topic's), else its stamp alone: the points beyond stay
  // as seen, as `eco run --data` leaves those of a cloud past its poses' end
  const double stamp = seconds_of(sweep.stamp_ns);
  const double reach = std::max(stamp, std::min(sweep.last, poses_->latest()));
  SweepPoses poses = poses_->sweep(sweep.frame_id, std::min(sweep.first, stamp), reach);
  if (poses.state != SweepPoses::State::Ready) poses = poses_->sweep(sweep.frame_id, stamp, stamp);
  if (poses.state == SweepPoses::State::Waiting) {
    poses.state = SweepPoses::State::Never;
    poses.why += " (waited ~tf_timeout, " + std::to_string(settings_.tf_timeout) + " s)";
  }
  return poses;
}

void EcoNode::take_ready() {
  while (!waiting_.empty()) {
    Waiting& cloud = waiting_.front();
    const DecodedSweep& sweep = cloud.sweep;
    SweepPoses poses = poses_->sweep(sweep.frame_id, sweep.first, sweep.last);
    if (poses.state == SweepPoses::State::Waiting) {
      if (ms_since(cloud.received) < 1e3 * settings_.tf_timeout) {
        retry_.start();  // looked at again as tf comes in, and once it waited too long
        return;
      }
      poses = poses_after_waiting(sweep);
    }
    if (poses.state == SweepPoses::State::Never) {
      ++skipped_;
      ROS_WARN_THROTTLE(1.0, "eco_node: cloud of %s at %.6f skipped, no pose: %s (%zu skipped so far)",
                        sweep.frame_id.c_str(), seconds_of(sweep.stamp_ns), poses.why.c_str(), skipped_);
    } else {
      const double first = sweep.first;
      const std::int64_t stamp_ns = sweep.stamp_ns;
      const double waited_ms = ms_since(cloud.received);
      hand_over(session_->take(std::move(cloud.sweep), poses.pose_at), stamp_ns, cloud.received, waited_ms);
      poses_->forget_before(first);
    }
    waiting_.pop_front();
  }
  retry_.stop();  // nothing waits
}

void EcoNode::take_by_odometry(Waiting cloud) {
  const std::string frame_id = cloud.sweep.frame_id;
  const ros::Time stamp = ros_time(cloud.sweep.stamp_ns);
  const double waited_ms = ms_since(cloud.received);
  TakenFrame taken = session_->take_by_odometry(std::move(cloud.sweep));
  nav_msgs::Odometry odom;
  odom.header.stamp = stamp;
  odom.header.frame_id = settings_.fixed_frame;
  odom.child_frame_id = frame_id;
  const geometry_msgs::Transform t = transform_of(taken.pose);
  odom.pose.pose.position.x = t.translation.x;
  odom.pose.pose.position.y = t.translation.y;
  odom.pose.pose.position.z = t.translation.z;
  odom.pose.pose.orientation = t.rotation;
  odom_.publish(odom);
  geometry_msgs::TransformStamped stamped;
  stamped.header = odom.header;
  stamped.child_frame_id = frame_id;
  stamped.transform = t;
  tf_broadcaster_.sendTransform(stamped);
  hand_over(std::move(taken), std::int64_t(stamp.toNSec()), cloud.received, waited_ms);
}

void EcoNode::hand_over(TakenFrame taken, std::int64_t stamp_ns, Clock::time_point received, double waited_ms) {
  const bool publish_map = taken.stats.frame % settings_.publish_every == 0;
  publisher_.offer({std::move(taken), ros_time(stamp_ns), received, waited_ms, ms_since(received), publish_map, lost_,
                    skipped_, refused_});
}

bool EcoNode::on_save(std_srvs::Trigger::Request& /*request*/, std_srvs::Trigger::Response& response) {
  try {
    session_->save(settings_.save_path);
    response.success = true;
    response.message = "saved " + std::to_string(session_->size()) + " points after " +
                       std::to_string(session_->frames()) + " frames to " + settings_.save_path;
  } catch (const std::exception& e) {
    response.success = false;
    response.message = e.what();
  }
  ROS_INFO("eco_node: ~save: %s", response.message.c_str());
  return true;
}

void EcoNode::finish() {
  retry_.stop();
  if (!waiting_.empty()) {
    ROS_WARN("eco_node: %zu clouds were still waiting for their poses when the node stopped: not taken", waiting_.size());
  }
  ROS_INFO("eco_node: %u frames taken; %zu clouds skipped without poses, %zu undecodable, %zu lost upstream; %zu points "
           "held", session_->frames(), skipped_, refused_, lost_, session_->size());
  if (settings_.save_on_exit) {
    session_->save(settings_.save_path);
    ROS_INFO("eco_node: saved the map to %s", settings_.save_path.c_str());
  }
}

}  // namespace eco::ros_node
