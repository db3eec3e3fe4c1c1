#include "io/ros/ros1_bag_store.hpp"
#include "io/ros/ros1_bag_frames.hpp"

#include <eco/io/error.hpp>

#ifdef ECO_HAS_ROSBAG
#include <rosbag/bag.h>
#include <rosbag/view.h>
#endif

#include <exception>
#include <map>
#include <new>

namespace eco::io::detail {

#ifdef ECO_HAS_ROSBAG

struct Ros1BagStore::Bag {
  rosbag::Bag bag;
  std::vector<rosbag::MessageInstance> messages;  // every message indexed so far, in order
};

namespace {

/// rosbag's failures as ours, naming the file.
template <class Work>
auto naming(const std::string& file, Work work) {
  try {
    return work();
  } catch (const rosbag::BagUnindexedException&) {
    throw Error(file, "", "has no index: it was cut short or never closed (rosbag reindex mends it)");
  } catch (const rosbag::BagException& e) {
    throw Error(file, "", std::string("cannot be read as a ROS 1 bag: ") + e.what());
  } catch (const ros::Exception& e) {
    throw Error(file, "", std::string("cannot be read as a ROS 1 bag: ") + e.what());
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw Error(file, "", "cannot be read as a ROS 1 bag: a record declares more bytes than can be held");
  } catch (const std::exception& e) {  // its decompressors' and boost's failures
    throw Error(file, "", std::string("cannot be read as a ROS 1 bag: ") + e.what());
  }
}

}  // namespace

bool Ros1BagStore::available() { return true; }

Ros1BagStore::Ros1BagStore(const std::filesystem::path& file) : name_(file.string()), bag_(std::make_unique<Bag>()) {
  if (!std::filesystem::is_regular_file(file)) throw Error(name_, "", "no such file");
  check_ros1_bag_frames(file);
  naming(name_, [&] { bag_->bag.open(name_, rosbag::bagmode::Read); });
}

Ros1BagStore::~Ros1BagStore() = default;

std::vector<TopicInfo> Ros1BagStore::topics() const {
  return naming(name_, [&] {
    std::map<std::string, TopicInfo> by_name;
    rosbag::View all(bag_->bag);
    for (const rosbag::ConnectionInfo* c : all.getConnections()) by_name.try_emplace(c->topic, TopicInfo{c->topic, c->datatype, 0});
    for (auto& [name, info] : by_name) info.messages = rosbag::View(bag_->bag, rosbag::TopicQuery(name)).size();
    std::vector<TopicInfo> out;
    for (auto& [name, info] : by_name) out.push_back(std::move(info));
    return out;
  });
}

std::vector<StoredMessage> Ros1BagStore::index(const std::string& topic) const {
  return naming(name_, [&] {
    std::vector<StoredMessage> out;
    rosbag::View view(bag_->bag, rosbag::TopicQuery(topic));
    for (const rosbag::MessageInstance& m : view) {
      const std::int64_t time = std::int64_t(m.getTime().toNSec());
      out.push_back({time, StoredMessage::kInFile, bag_->messages.size(), m.size(), 0});
      bag_->messages.push_back(m);
    }
    return out;
  });
}

std::span<const std::uint8_t> Ros1BagStore::read(const StoredMessage& message) {
  return naming(name_, [&]() -> std::span<const std::uint8_t> {
    if (message.offset >= bag_->messages.size()) throw Error(name_, "", "message " + std::to_string(message.offset) + " was not indexed");
    const rosbag::MessageInstance& m = bag_->messages[message.offset];
    buffer_.resize(m.size());
    ros::serialization::OStream stream(buffer_.data(), std::uint32_t(buffer_.size()));
    m.write(stream);
    return buffer_;
  });
}

#else  // built without Debian's rosbag_storage

struct Ros1BagStore::Bag {};

bool Ros1BagStore::available() { return false; }

Ros1BagStore::Ros1BagStore(const std::filesystem::path& file) : name_(file.string()) {
  throw Error(name_, "", "is a ROS 1 bag, and this eco was built without Debian's librosbag-storage-dev");
}

Ros1BagStore::~Ros1BagStore() = default;
std::vector<TopicInfo> Ros1BagStore::topics() const { return {}; }
std::vector<StoredMessage> Ros1BagStore::index(const std::string&) const { return {}; }
std::span<const std::uint8_t> Ros1BagStore::read(const StoredMessage&) { return {}; }

#endif

}  // namespace eco::io::detail
