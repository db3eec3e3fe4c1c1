// Recordings written by other people's code (foxglove's MCAP and CDR writers, SQLite in rosbag2's
// schema: tests/io/recordings/) read back cloud by cloud, each point, intensity and time against
// what the writer put in (ROS 1 bags written by Debian's rosbag too); drivers' layouts found by name, type and value; damage refused or, for a
// file cut short, read up to the cut and named.

#include <eco/io/error.hpp>
#include <eco/io/recording.hpp>
#include <eco/workloads/scan_source.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <filesystem>
#include <fstream>
#include <string>

namespace eco::io {
namespace {

namespace fs = std::filesystem;

fs::path recordings() {
  const char* dir = std::getenv("ECO_RECORDINGS");
  return dir ? fs::path(dir) : fs::path();
}

const nlohmann::json& expected() {
  static const nlohmann::json json = nlohmann::json::parse(std::ifstream(recordings() / "expected.json"));
  return json;
}

/// The ROS 1 bags' (write_ros1_bags.py, with Debian's rosbag).
const nlohmann::json& ros1_expected() {
  static const nlohmann::json json = nlohmann::json::parse(std::ifstream(recordings() / "ros1_expected.json"));
  return json;
}

class RecordingTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (recordings().empty() || !fs::exists(recordings() / "expected.json")) {
      GTEST_FAIL() << "ECO_RECORDINGS names no folder of test recordings (write_recordings.sh writes them)";
    }
  }
  void TearDown() override { fs::remove_all(scratch_folder()); }

 public:
  /// Where a test writes the damaged copies it reads (damaged_copy), gone after each test.
  static fs::path scratch_folder() { return fs::temp_directory_path() / ("eco-recording-test-" + std::to_string(getpid())); }
};

/// Every cloud of `topic` in `path` as the writer described it, in order.
void expect_clouds(const fs::path& path, const std::string& topic, const nlohmann::json& clouds, Recording& bag) {
  SCOPED_TRACE(path.string() + " " + topic);
  ASSERT_EQ(bag.topic(), topic);
  ASSERT_EQ(bag.size(), clouds.size());
  for (std::size_t i = 0; i < bag.size(); ++i) {
    const RecordedScan scan = bag.read(i);
    const nlohmann::json& want = clouds[i];
    EXPECT_EQ(std::to_string(scan.stamp_ns), want["stamp_ns"].get<std::string>());
    EXPECT_EQ(scan.frame_id, "lidar");
    ASSERT_EQ(scan.cloud.points.size(), want["points"].size()) << "cloud " << i;
    for (std::size_t p = 0; p < scan.cloud.points.size(); ++p) {
      for (int c = 0; c < 3; ++c) ASSERT_EQ(scan.cloud.points[p][c], float(want["points"][p][c].get<double>())) << i << "/" << p;
    }
    ASSERT_EQ(scan.cloud.intensities.size(), want["intensities"].size());
    for (std::size_t p = 0; p < scan.cloud.intensities.size(); ++p) {
      ASSERT_EQ(scan.cloud.intensities[p], float(want["intensities"][p].get<double>())) << i << "/" << p;
    }
    ASSERT_EQ(scan.cloud.times.size(), want["times"].size());
    for (std::size_t p = 0; p < scan.cloud.times.size(); ++p) {
      ASSERT_EQ(scan.cloud.times[p], want["times"][p].get<double>()) << i << "/" << p;
    }
    // the writer left out every 50th point (not finite) and every 61st (at the origin)
    EXPECT_GT(scan.cloud.skipped_not_finite, 0u);
    EXPECT_GT(scan.cloud.skipped_zero, 0u);
  }
}

TEST_F(RecordingTest, EveryFileAndTopicAsWritten) {
  std::size_t topics = 0;
  for (const auto& [file, by_topic] : expected().items()) {
    for (const auto& [topic, content] : by_topic.items()) {
      const fs::path path = recordings() / file;
      Recording bag(path, {topic, {}});
      expect_clouds(path, topic, content["clouds"], bag);
      ++topics;
    }
  }
  EXPECT_GE(topics, 12u);
}

TEST_F(RecordingTest, ASplitRosbag2FolderReadsAsOne) {
  Recording bag(recordings() / "ouster_bag", {});
  expect_clouds(recordings() / "ouster_bag", "/ouster/points", expected()["ouster.db3"]["/ouster/points"]["clouds"], bag);
  EXPECT_NE(bag.describe().find("rosbag2 folder, 2 files"), std::string::npos) << bag.describe();
}

TEST_F(RecordingTest, DriversTimeLayoutsAreFound) {
  struct Case {
    const char* file;
    const char* field;
    TimeUnit unit;
    bool absolute;
    const char* intensity;
  };
  for (const Case& c : {Case{"ouster_zstd.mcap", "t", TimeUnit::Nanoseconds, false, "intensity"},
                        Case{"velodyne.mcap", "time", TimeUnit::Seconds, false, "intensity"},
                        Case{"hesai.mcap", "timestamp", TimeUnit::Seconds, true, "intensity"},
                        Case{"robosense.mcap", "timestamp", TimeUnit::Seconds, true, "intensity"},
                        Case{"livox.mcap", "offset_time", TimeUnit::Nanoseconds, false, "reflectivity"},
                        Case{"plain.mcap", "", TimeUnit::Auto, false, ""}}) {
    Recording bag(recordings() / c.file, {});
    (void)bag.read(0);
    ASSERT_TRUE(bag.layout()) << c.file;
    EXPECT_EQ(bag.layout()->time_field, c.field) << c.file;
    EXPECT_EQ(bag.layout()->intensity_field, c.intensity) << c.file;
    if (*c.field) {
      EXPECT_EQ(bag.layout()->time_unit, c.unit) << c.file;
      EXPECT_EQ(bag.layout()->absolute_times, c.absolute) << c.file;
    }
  }
}

TEST_F(RecordingTest, TheTimeFieldAndUnitCanBeForced) {
  // velodyne's ring (uint16) taken as a time in microseconds
  Recording bag(recordings() / "velodyne.mcap", {"", {"ring", TimeUnit::Microseconds}});
  const RecordedScan scan = bag.read(0);
  EXPECT_EQ(bag.layout()->time_field, "ring");
  ASSERT_FALSE(scan.cloud.times.empty());
  for (double t : scan.cloud.times) EXPECT_LT(t, 32e-6);
  try {
    Recording missing(recordings() / "velodyne.mcap", {"", {"stamp_us", TimeUnit::Auto}});
    (void)missing.read(0);
    FAIL() << "a missing time field was taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("has no time field stamp_us"), std::string::npos) << e.what();
  }
}

std::string error_of(const fs::path& path, const std::string& topic = "") {
  try {
    Recording bag(path, {topic, {}});
    for (std::size_t i = 0; i < bag.size(); ++i) (void)bag.read(i);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST_F(RecordingTest, TopicsAreListedWhenTheChoiceIsOpenOrWrong) {
  const std::string several = error_of(recordings() / "two_lidars.mcap");
  EXPECT_NE(several.find("several PointCloud2 topics: pick one with --topic"), std::string::npos) << several;
  for (const char* line : {"/front/points", "/rear/points", "/odom", "geometry_msgs/msg/Point", "3 messages", "4 messages"}) {
    EXPECT_NE(several.find(line), std::string::npos) << line << " in " << several;
  }
  const std::string missing = error_of(recordings() / "two_lidars.mcap", "/points");
  EXPECT_NE(missing.find("has no topic /points; its topics:"), std::string::npos) << missing;
  const std::string wrong = error_of(recordings() / "two_lidars.mcap", "/odom");
  EXPECT_NE(wrong.find("holds geometry_msgs/msg/Point, not sensor_msgs/PointCloud2"), std::string::npos) << wrong;
  EXPECT_NE(error_of(recordings() / "no_clouds.mcap").find("has no sensor_msgs/PointCloud2 topic"), std::string::npos);
  EXPECT_NE(error_of(recordings() / "empty.mcap").find("(no topics)"), std::string::npos);
  Recording rear(recordings() / "two_lidars.mcap", {"/rear/points", {}});
  EXPECT_EQ(rear.size(), 2u);
}

/// `source` copied to `name` in a scratch folder, then changed by `edit`.
fs::path damaged_copy(const std::string& source, const std::string& name, const std::function<void(std::string&)>& edit) {
  std::ifstream in(recordings() / source, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  edit(bytes);
  const fs::path out = RecordingTest::scratch_folder() / name;
  fs::create_directories(out.parent_path());
  std::ofstream(out, std::ios::binary) << bytes;
  return out;
}

TEST_F(RecordingTest, ACutFileIsReadUpToTheCutAndSaysWhere) {
  const std::uintmax_t size = fs::file_size(recordings() / "ouster_none.mcap");
  const nlohmann::json& clouds = expected()["ouster_none.mcap"]["/ouster/points"]["clouds"];
  std::size_t whole_seen = 0;
  for (std::uintmax_t cut = 40; cut < size; cut += size / 37) {
    const fs::path path = damaged_copy("ouster_none.mcap", "cut.mcap", [&](std::string& b) { b.resize(std::size_t(cut)); });
    try {
      Recording bag(path, {"/ouster/points", {}});
      EXPECT_NE(bag.damage().find("the file ends"), std::string::npos) << cut;
      EXPECT_NE(bag.damage().find("cut.mcap: byte "), std::string::npos) << bag.damage();
      ASSERT_LE(bag.size(), clouds.size());
      for (std::size_t i = 0; i < bag.size(); ++i) {
        const RecordedScan scan = bag.read(i);
        ASSERT_EQ(scan.cloud.points.size(), clouds[i]["points"].size()) << "cut at " << cut;
      }
      whole_seen = std::max(whole_seen, bag.size());
    } catch (const Error& e) {  // cut inside the first chunk, which defines the topic
      EXPECT_NE(std::string(e.what()).find("(no topics)"), std::string::npos) << "cut at " << cut << ": " << e.what();
    }
  }
  EXPECT_GE(whole_seen, 4u);
  // cut before the first record: nothing to read, and said
  const fs::path head = damaged_copy("ouster_none.mcap", "head.mcap", [](std::string& b) { b.resize(8); });
  EXPECT_NE(error_of(head).find("(no topics)"), std::string::npos);
}

TEST_F(RecordingTest, DamageIsRefusedNamingTheFileAndByte) {
  const std::string not_mcap = error_of(damaged_copy("ouster_none.mcap", "not.mcap", [](std::string& b) { b[1] = 'X'; }));
  EXPECT_NE(not_mcap.find("not.mcap: byte 0: not an MCAP file"), std::string::npos) << not_mcap;

  // a byte of a cloud flipped inside an uncompressed chunk: its CRC-32 no longer matches
  const std::string crc = error_of(damaged_copy("ouster_none.mcap", "crc.mcap", [](std::string& b) { b[b.size() / 3] ^= 0x10; }));
  EXPECT_NE(crc.find("crc.mcap: byte "), std::string::npos) << crc;
  EXPECT_NE(crc.find("CRC-32"), std::string::npos) << crc;

  const std::string compression = error_of(damaged_copy("ouster_zstd.mcap", "brotli.mcap", [](std::string& b) {
    for (std::size_t at = b.find("zstd"); at != std::string::npos; at = b.find("zstd", at)) b.replace(at, 4, "brot");
  }));
  EXPECT_NE(compression.find("compression 'brot' is not one of lz4, zstd or none"), std::string::npos) << compression;

  const std::string lz4 = error_of(damaged_copy("ouster_lz4.mcap", "lz4.mcap", [](std::string& b) {
    for (std::size_t at = b.size() / 4; at < b.size() / 4 + 64; ++at) b[at] = char(0xff);
  }));
  EXPECT_NE(lz4.find("lz4.mcap: byte "), std::string::npos) << lz4;

  // a chunk declaring 4 GiB once decompressed: refused before anything that size is allocated
  for (const char* file : {"ouster_none.mcap", "ouster_lz4.mcap", "ouster_zstd.mcap"}) {
    const std::string huge = error_of(damaged_copy(file, "huge.mcap", [](std::string& b) {
      for (std::size_t at = 8; at + 9 <= b.size();) {  // records: op, u64 length, body
        std::uint64_t length = 0;
        std::memcpy(&length, &b[at + 1], 8);
        if (b[at] == 0x06) {  // a chunk: start time, end time, then uncompressed_size
          const std::uint64_t declared = std::uint64_t(1) << 32;
          std::memcpy(&b[at + 9 + 16], &declared, 8);
          return;
        }
        at += 9 + std::size_t(length);
      }
      FAIL() << "no chunk";
    }));
    EXPECT_NE(huge.find("uncompressed_size 4294967296 is not believable for "), std::string::npos) << file << ": " << huge;
  }

  EXPECT_NE(error_of(recordings() / "missing.mcap").find("missing.mcap"), std::string::npos);
  const std::string not_db3 = error_of(damaged_copy("ouster_none.mcap", "not.db3", [](std::string&) {}));
  EXPECT_NE(not_db3.find("not.db3"), std::string::npos) << not_db3;
}

TEST_F(RecordingTest, Ros1BagsWrittenByRosbagAsWritten) {
  std::size_t topics = 0;
  for (const auto& [file, by_topic] : ros1_expected().items()) {
    for (const auto& [topic, content] : by_topic.items()) {
      const fs::path path = recordings() / file;
      Recording bag(path, {topic, {}});
      expect_clouds(path, topic, content["clouds"], bag);
      ++topics;
    }
  }
  EXPECT_EQ(topics, 7u);  // uncompressed, bz2, lz4; a split pair; two lidars; beside tf
  EXPECT_NE(Recording(recordings() / "split_bags", {}).describe().find("ROS 1 bags, 2 files"), std::string::npos);
  EXPECT_NE(Recording(recordings() / "ouster_lz4.bag", {}).describe().find("(ROS 1 bag)"), std::string::npos);
}

TEST_F(RecordingTest, Ros1TopicsAreListedAndDamageNamed) {
  const std::string several = error_of(recordings() / "two_lidars.bag");
  EXPECT_NE(several.find("several PointCloud2 topics"), std::string::npos) << several;
  for (const char* line : {"/front/points", "/rear/points", "/odom", "nav_msgs/Odometry", "sensor_msgs/PointCloud2", "4 messages"}) {
    EXPECT_NE(several.find(line), std::string::npos) << line << " in " << several;
  }
  const std::string wrong = error_of(recordings() / "two_lidars.bag", "/odom");
  EXPECT_NE(wrong.find("holds nav_msgs/Odometry, not sensor_msgs/PointCloud2"), std::string::npos) << wrong;
  // cut short: its index, written last, is gone
  const fs::path cut = damaged_copy("ouster_none.bag", "cut.bag", [](std::string& b) { b.resize(b.size() / 2); });
  const std::string unindexed = error_of(cut);
  EXPECT_NE(unindexed.find("cut.bag: "), std::string::npos) << unindexed;
  EXPECT_NE(error_of(damaged_copy("ouster_none.mcap", "not_a.bag", [](std::string&) {})).find("not_a.bag: "), std::string::npos);
  // records that declare more than they hold, refused by their framing before rosbag allocates it
  const auto set_field = [](const char* name, std::uint32_t value) {
    return [=](std::string& b) {
      const std::size_t at = b.find(std::string(name) + "=");
      ASSERT_NE(at, std::string::npos) << name;
      std::memcpy(&b[at + std::strlen(name) + 1], &value, 4);
    };
  };
  const std::string huge = error_of(damaged_copy("ouster_none.bag", "huge_chunk.bag", set_field("size", 0xFFFFFFF0u)));
  EXPECT_NE(huge.find("huge_chunk.bag: byte "), std::string::npos) << huge;
  EXPECT_NE(huge.find("a chunk declares more than 1 GiB once uncompressed"), std::string::npos) << huge;
  const std::string cut_early = error_of(damaged_copy("ouster_none.bag", "cut_early.bag", [](std::string& b) { b.resize(5000); }));
  EXPECT_NE(cut_early.find("cut_early.bag: byte 13: the bag header's index lies at byte "), std::string::npos) << cut_early;
  EXPECT_NE(cut_early.find("past the end (5000 bytes): the bag is cut short (rosbag reindex mends that)"), std::string::npos)
      << cut_early;
  std::uint64_t second = 0;  // the record after the bag header: its header's length made 2 GB
  const fs::path long_header = damaged_copy("ouster_none.bag", "long_header.bag", [&](std::string& b) {
    std::uint32_t header = 0, data = 0;
    std::memcpy(&header, &b[13], 4);
    std::memcpy(&data, &b[13 + 4 + header], 4);
    second = 13 + 4 + header + 4 + data;
    const std::uint32_t declared = 0x7FFFFFFF;
    std::memcpy(&b[second], &declared, 4);
  });
  const std::string too_long = error_of(long_header);
  EXPECT_NE(too_long.find("long_header.bag: byte " + std::to_string(second) + ": a record's header declares 2147483647 bytes"),
            std::string::npos)
      << too_long;
}

TEST_F(RecordingTest, APoseTopicPlacesEachCloudAtItsStamp) {
  for (const char* topic : {"/odom", "/pose"}) {  // nav_msgs/msg/Odometry, geometry_msgs/msg/PoseStamped
    SCOPED_TRACE(topic);
    Recording bag(recordings() / "posed.mcap", {});
    ASSERT_EQ(bag.pose_topics().size(), 2u);
    const PoseStream stream = bag.pose_track(topic);
    const PoseTrack& track = stream.track;
    ASSERT_EQ(track.poses.size(), 6u);
    EXPECT_EQ(stream.frame_id, "odom");
    EXPECT_EQ(stream.child_frame_id, std::string(topic) == "/odom" ? "lidar" : "");
    EXPECT_DOUBLE_EQ(track.times[0], 1700000000.0 - 0.05);
    // the writer's poses, half a frame off the clouds': x = 10 m/s × t, yaw = 0.5 rad/s × t
    workloads::SourceOptions options;
    options.pose_topic = topic;
    const workloads::OpenedSource source = workloads::open_source(recordings() / "posed.mcap", options);
    ASSERT_TRUE(source.has_poses);
    ASSERT_EQ(source.size(), 4u);
    for (std::size_t k = 0; k < 4; ++k) {
      const Eigen::Isometry3d pose = source.frames->pose(k);
      const double t = 0.1 * double(k);
      EXPECT_NEAR(pose.translation().x(), 10.0 * t, 1e-5) << k;  // seconds since 1970 in a double: 0.24 µs steps
      EXPECT_NEAR(std::atan2(pose.linear()(1, 0), pose.linear()(0, 0)), 0.5 * t, 1e-6) << k;
    }
    // the odometry's child frame is the clouds': nothing to warn of; PoseStamped names none
    ASSERT_EQ(source.warnings.size(), std::string(topic) == "/odom" ? 0u : 1u);
  }
  // a ROS 1 bag's nav_msgs/Odometry, at the clouds' own stamps: x = k
  workloads::SourceOptions options;
  options.recording.topic = "/front/points";
  options.pose_topic = "/odom";
  const workloads::OpenedSource front = workloads::open_source(recordings() / "two_lidars.bag", options);
  ASSERT_EQ(front.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(front.frames->pose(k).translation().x(), double(k), 1e-9) << k;
}

TEST_F(RecordingTest, APoseTopicThatIsNoneIsRefusedByName) {
  Recording bag(recordings() / "posed.mcap", {});
  const auto refusal = [&](const std::string& topic) {
    try {
      (void)bag.pose_track(topic);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(refusal("/points").find("topic /points holds sensor_msgs/msg/PointCloud2, not nav_msgs/Odometry"), std::string::npos);
  EXPECT_NE(refusal("/tf").find("has no topic /tf; its topics:"), std::string::npos);
  workloads::SourceOptions both;
  both.pose_topic = "/odom";
  both.poses = (recordings() / "expected.json").string();
  try {
    (void)workloads::open_source(recordings() / "posed.mcap", both);
    ADD_FAILURE() << "--poses and --pose-topic were both taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--poses and --pose-topic both give poses"), std::string::npos) << e.what();
  }
  const workloads::OpenedSource unposed = workloads::open_source(recordings() / "posed.mcap", {});
  EXPECT_FALSE(unposed.has_poses);
  EXPECT_EQ(unposed.pose_topics, (std::vector<std::string>{"/odom (nav_msgs/msg/Odometry)", "/pose (geometry_msgs/msg/PoseStamped)"}));
}

/// The motion tf.mcap and tf.bag hold (write_mcap.mjs, write_ros1_bags.py): `frame`'s pose in
/// map (or in odom, without map -> odom's (0, 5, 0)) t seconds after the first cloud.
Eigen::Isometry3d tf_pose(const std::string& fixed, const std::string& frame, double t) {
  const Eigen::Isometry3d map_T_odom(Eigen::Translation3d(0, 5, 0));
  const Eigen::Isometry3d odom_T_base = Eigen::Translation3d(10 * t, 0, 0) * Eigen::AngleAxisd(0.5 * t, Eigen::Vector3d::UnitZ());
  const Eigen::Isometry3d base_T_lidar = Eigen::Translation3d(1, 0, 2) * Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ());
  const Eigen::Isometry3d odom_T_frame = frame == "lidar" ? odom_T_base * base_T_lidar : odom_T_base;
  return fixed == "map" ? map_T_odom * odom_T_frame : odom_T_frame;
}

void expect_pose(const Eigen::Isometry3d& got, const Eigen::Isometry3d& want, const std::string& what) {
  // seconds since 1970 in a double: 0.24 µs steps, 2.4 µm at 10 m/s
  EXPECT_LT((got.translation() - want.translation()).norm(), 1e-5) << what;
  EXPECT_LT((got.linear() - want.linear()).cwiseAbs().maxCoeff(), 1e-6) << what;
}

workloads::OpenedSource opened(const fs::path& path, const std::string& pose_topic, const std::string& fixed_frame = "",
                               bool place_points = false) {
  workloads::SourceOptions options;
  options.pose_topic = pose_topic;
  options.fixed_frame = fixed_frame;
  options.place_points = place_points;
  return workloads::open_source(path, options);
}

TEST_F(RecordingTest, TfPlacesEachCloudThroughItsChainOfFrames) {
  for (const char* file : {"tf.mcap", "tf.bag"}) {
    SCOPED_TRACE(file);
    for (const std::string fixed : {"", "map", "odom"}) {
      const workloads::OpenedSource source = opened(recordings() / file, "tf", fixed);
      ASSERT_TRUE(source.has_poses);
      ASSERT_EQ(source.size(), 4u);
      const std::string chain = fixed == "odom" ? "tf: odom -> base_link -> lidar" : "tf: map -> odom -> base_link -> lidar";
      EXPECT_NE(source.description.find("; poses: " + chain), std::string::npos) << source.description;
      EXPECT_TRUE(source.warnings.empty()) << source.warnings.front();
      for (std::size_t k = 0; k < 4; ++k) {
        expect_pose(source.frames->pose(k), tf_pose(fixed.empty() ? "map" : fixed, "lidar", 0.1 * double(k)),
                    fixed + " " + std::to_string(k));
      }
    }
    // a frame beside the chain: the camera, on another branch of base_link, sees the LiDAR fixed
    const workloads::OpenedSource camera = opened(recordings() / file, "tf", "camera");
    EXPECT_NE(camera.description.find("tf: camera <- base_link -> lidar"), std::string::npos) << camera.description;
    expect_pose(camera.frames->pose(3), Eigen::Translation3d(0.5, 0, 1.0) * Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()),
                "camera");
    try {
      (void)opened(recordings() / file, "tf", "gps");
      ADD_FAILURE() << "a fixed frame outside the tree was taken";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("no chain of transforms joins gps and lidar; the frames are: base_link, camera, lidar, "
                                           "map, odom"),
                std::string::npos)
          << e.what();
    }
  }
  try {
    (void)opened(recordings() / "tf.mcap", "/odom", "map");
    ADD_FAILURE() << "--fixed-frame was taken without --pose-topic tf";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--fixed-frame map is for --pose-topic tf"), std::string::npos) << e.what();
  }
  try {
    (void)opened(recordings() / "posed.mcap", "tf");
    ADD_FAILURE() << "a recording without tf gave tf's poses";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("has no /tf or /tf_static topic of tf2_msgs/TFMessage; its topics:"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(opened(recordings() / "tf.bag", "").pose_topics.back(), "tf (/tf and /tf_static, from --fixed-frame to the clouds' frame)");
}

TEST_F(RecordingTest, APoseTopicReachesTheCloudsFrameThroughTf) {
  // /odom places base_link in odom; tf_static's base_link -> lidar takes it to the clouds' frame
  const workloads::OpenedSource source = opened(recordings() / "tf.mcap", "/odom");
  EXPECT_NE(source.description.find("poses: /odom (base_link in odom), then tf: base_link -> lidar"), std::string::npos)
      << source.description;
  EXPECT_TRUE(source.warnings.empty()) << source.warnings.front();
  for (std::size_t k = 0; k < 4; ++k) expect_pose(source.frames->pose(k), tf_pose("odom", "lidar", 0.1 * double(k)), std::to_string(k));
  // without tf to link the frames, the poses are taken as they are, and the user told so
  const workloads::OpenedSource bare = opened(recordings() / "posed.mcap", "/pose");
  ASSERT_FALSE(bare.warnings.empty());
  EXPECT_NE(bare.warnings.back().find("the poses of /pose (the pose in odom) are taken as the LiDAR's (lidar): no tf in the "
                                      "recording links them"),
            std::string::npos)
      << bare.warnings.back();
}

TEST_F(RecordingTest, EachPointIsPlacedByThePoseAtItsOwnTime) {
  const std::pair<const char*, const nlohmann::json*> files[] = {{"tf.mcap", &expected()["tf.mcap"]["/points"]["clouds"]},
                                                                 {"tf.bag", &ros1_expected()["tf.bag"]["/points"]["clouds"]}};
  for (const auto& [file, clouds] : files) {
    SCOPED_TRACE(file);
    const workloads::OpenedSource placed = opened(recordings() / file, "tf", "", true);
    const workloads::OpenedSource as_seen = opened(recordings() / file, "tf", "", false);
    ASSERT_EQ(placed.size(), clouds->size());
    for (std::size_t k = 0; k < placed.size(); ++k) {
      const workloads::WorkloadFrame frame = placed.frames->frame(k), raw = as_seen.frames->frame(k);
      const nlohmann::json& want = (*clouds)[k];
      ASSERT_EQ(frame.points.size(), want["points"].size());
      EXPECT_TRUE(frame.point_times.empty()) << "placed points have nothing left to deskew";
      ASSERT_EQ(raw.point_times.size(), raw.points.size());
      const double t = 0.1 * double(k);
      const Eigen::Isometry3d stamp_T_map = tf_pose("map", "lidar", t).inverse();
      double largest_move = 0.0;
      for (std::size_t i = 0; i < frame.points.size(); ++i) {
        const Eigen::Vector3d seen(want["points"][i][0].get<double>(), want["points"][i][1].get<double>(), want["points"][i][2].get<double>());
        ASSERT_EQ(raw.points[i].cast<double>(), seen.cast<float>().cast<double>()) << "unplaced points stay as seen";
        const double tau = want["times"][i].get<double>();
        const Eigen::Vector3d expect = stamp_T_map * tf_pose("map", "lidar", t + tau) * seen;
        ASSERT_LT((frame.points[i].cast<double>() - expect).norm(), 2e-5) << k << "/" << i << " at " << tau;
        largest_move = std::max(largest_move, (expect - seen).norm());
      }
      EXPECT_GT(largest_move, 0.5) << "the sweep's motion moves its last points by about a metre";
    }
  }
}

}  // namespace
}  // namespace eco::io
