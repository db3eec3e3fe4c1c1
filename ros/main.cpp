// eco_node: ECO's map of a live ROS 1 point-cloud stream (eco_node.hpp). `eco_node --help` lists
// the parameters; a bad one stops the node at start (exit 2), named with its value.

#include "eco_node.hpp"

#include <eco/process_heap.hpp>

#include <ros/callback_queue.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <sstream>

namespace {

std::atomic<bool> interrupted{false};  // SIGINT: the node finishes (logs, saves) while ROS is still up

/// A parameter's value as text, as the parameters' table reads it.
std::string text_of(XmlRpc::XmlRpcValue value, const std::string& name) {
  std::ostringstream s;
  s.precision(17);
  switch (value.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean: return bool(value) ? "true" : "false";
    case XmlRpc::XmlRpcValue::TypeInt: return std::to_string(int(value));
    case XmlRpc::XmlRpcValue::TypeDouble: s << double(value); return s.str();
    case XmlRpc::XmlRpcValue::TypeString: return std::string(value);
    default: throw std::invalid_argument("~" + name + " = " + value.toXml() + ": not a number, true/false or text");
  }
}

/// The map and node that the private parameters describe.
std::unique_ptr<eco::ros_node::MapSession> session_from_parameters(const ros::NodeHandle& private_node) {
  std::vector<std::string> names, given;
  ros::param::getParamNames(names);
  const std::string prefix = ros::this_node::getName() + "/";
  for (const std::string& n : names) {
    if (n.compare(0, prefix.size(), prefix) == 0) given.push_back(n.substr(prefix.size()));
  }
  return std::make_unique<eco::ros_node::MapSession>(
      [&](const std::string& name) -> std::optional<std::string> {
        XmlRpc::XmlRpcValue value;
        if (!private_node.getParam(name, value)) return std::nullopt;
        return text_of(value, name);
      },
      given);
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
      std::printf("eco_node: ECO's map of a live sensor_msgs/PointCloud2 stream.\n"
                  "  eco_node _cloud_topic:=/points _pose_topic:=/odom _box_side:=40\n"
                  "Publishes ~map and ~voxels (sensor_msgs/PointCloud2 in ~fixed_frame), ~region "
                  "(visualization_msgs/Marker), ~stats (std_msgs/String, a JSON object a frame), and with ~odometry "
                  "~odom (nav_msgs/Odometry) and tf; serves ~save (std_srvs/Trigger).\nParameters:\n%s",
                  eco::ros_node::MapSession::help().c_str());
      return 0;
    }
  }
  eco::keep_freed_heap();  // a frame's large buffers kept by the C library, as beside a map on the heap
  ros::init(argc, argv, "eco_node", ros::init_options::NoSigintHandler);
  std::signal(SIGINT, [](int) { interrupted = true; });
  ros::NodeHandle node, private_node("~");
  std::unique_ptr<eco::ros_node::MapSession> session;
  try {
    session = session_from_parameters(private_node);
  } catch (const std::invalid_argument& e) {
    ROS_FATAL("eco_node: %s", e.what());
    return 2;
  }
  try {
    eco::ros_node::EcoNode eco_node(node, private_node, std::move(session));
    while (ros::ok() && !interrupted) {  // until SIGINT or rosnode kill; each callback as it comes
      ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.05));
    }
    eco_node.finish();
  } catch (const std::exception& e) {
    ROS_FATAL("eco_node: %s", e.what());
    return 1;
  }
  ros::shutdown();
  return 0;
}
