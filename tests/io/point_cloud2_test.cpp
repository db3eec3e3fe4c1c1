// PointCloud2's checks, each on a cloud made by hand: what is refused names the source and the
// fault (no x/y/z, a field past point_step, row_step or data too short, big-endian, a datatype
// out of range, a message cut short at any byte), and what is read is read exactly (fields at odd
// offsets, organised rows with padding, float64 coordinates, non-finite and zero points counted).

#include <eco/io/error.hpp>
#include <eco/io/point_cloud2.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace eco::io {
namespace {

/// A cloud of `points` in rows of `width`, x y z as float32 at 1, 5, 9 and a uint16 `ring` at
/// 13 (odd offsets), each row padded by 3 bytes.
struct HandCloud {
  std::vector<std::uint8_t> bytes;
  PointCloud2 cloud;

  HandCloud(const std::vector<Eigen::Vector3f>& points, std::uint32_t width) {
    cloud.width = width;
    cloud.height = std::uint32_t(points.size() / width);
    cloud.point_step = 15;
    cloud.row_step = width * 15 + 3;
    cloud.fields = {{"x", 1, FieldType::Float32, 1}, {"y", 5, FieldType::Float32, 1}, {"z", 9, FieldType::Float32, 1},
                    {"ring", 13, FieldType::UInt16, 1}};
    bytes.assign(std::size_t(cloud.height) * cloud.row_step, 0xAB);
    for (std::size_t i = 0; i < points.size(); ++i) {
      std::uint8_t* p = bytes.data() + (i / width) * cloud.row_step + (i % width) * cloud.point_step;
      std::memcpy(p + 1, &points[i].x(), 4);
      std::memcpy(p + 5, &points[i].y(), 4);
      std::memcpy(p + 9, &points[i].z(), 4);
      const std::uint16_t ring = std::uint16_t(i);
      std::memcpy(p + 13, &ring, 2);
    }
    cloud.data = bytes;
  }
};

std::string refusal(const PointCloud2& cloud) {
  try {
    CloudDecoder decoder;
    (void)decoder.decode(cloud, "bag.mcap, /points message 3");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(PointCloud2, AnOrganisedCloudAtOddOffsetsIsReadExactly) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<Eigen::Vector3f> points{{1, 2, 3}, {nan, 0, 0}, {4.5f, -1, 0.25f}, {0, 0, 0}, {-7, 8, 9}, {1e-3f, 0, 0}};
  HandCloud hand(points, 3);
  CloudDecoder decoder({"ring", TimeUnit::Microseconds});
  const DecodedCloud out = decoder.decode(hand.cloud, "hand");
  EXPECT_EQ(out.points, (std::vector<Eigen::Vector3f>{{1, 2, 3}, {4.5f, -1, 0.25f}, {-7, 8, 9}, {1e-3f, 0, 0}}));
  EXPECT_EQ(out.skipped_not_finite, 1u);
  EXPECT_EQ(out.skipped_zero, 1u);
  EXPECT_EQ(out.times, (std::vector<double>{0 * 1e-6, 2 * 1e-6, 4 * 1e-6, 5 * 1e-6}));  // ring × 1 µs
  EXPECT_TRUE(out.intensities.empty());
  EXPECT_EQ(decoder.layout()->describe(), "time: field ring in us after the header stamp; intensity: none");
}

TEST(PointCloud2, Float64CoordinatesAreRead) {
  std::vector<std::uint8_t> bytes(2 * 24);
  const double values[6] = {1.25, -2.5, 3.0, 1e6, 2e-3, -4.0};
  std::memcpy(bytes.data(), values, sizeof values);
  PointCloud2 cloud;
  cloud.width = 2;
  cloud.height = 1;
  cloud.point_step = 24;
  cloud.row_step = 48;
  cloud.fields = {{"x", 0, FieldType::Float64, 1}, {"y", 8, FieldType::Float64, 1}, {"z", 16, FieldType::Float64, 1}};
  cloud.data = bytes;
  CloudDecoder decoder;
  EXPECT_EQ(decoder.decode(cloud, "f64").points, (std::vector<Eigen::Vector3f>{{1.25f, -2.5f, 3.0f}, {1e6f, 2e-3f, -4.0f}}));
}

TEST(PointCloud2, EachFaultIsRefusedByName) {
  const std::vector<Eigen::Vector3f> points(4, Eigen::Vector3f(1, 2, 3));
  {
    HandCloud hand(points, 2);
    hand.cloud.fields.erase(hand.cloud.fields.begin() + 1);
    EXPECT_EQ(refusal(hand.cloud), "bag.mcap, /points message 3: PointCloud2 has no x, y and z fields");
  }
  {
    HandCloud hand(points, 2);
    hand.cloud.point_step = 14;
    EXPECT_EQ(refusal(hand.cloud),
              "bag.mcap, /points message 3: PointCloud2 field ring (uint16 at 13) ends past point_step 14");
  }
  {
    HandCloud hand(points, 2);
    hand.cloud.row_step = 29;
    EXPECT_EQ(refusal(hand.cloud), "bag.mcap, /points message 3: PointCloud2 row_step 29 is shorter than width 2 × point_step 15");
  }
  {
    HandCloud hand(points, 2);
    hand.cloud.data = std::span<const std::uint8_t>(hand.bytes).first(hand.bytes.size() - 1);
    EXPECT_EQ(refusal(hand.cloud), "bag.mcap, /points message 3: PointCloud2 data holds 65 bytes, less than height 2 × row_step 33");
  }
  {
    HandCloud hand(points, 2);
    hand.cloud.is_bigendian = true;
    EXPECT_EQ(refusal(hand.cloud), "bag.mcap, /points message 3: PointCloud2 is big-endian: only little-endian clouds are read");
  }
}

/// A ROS 1 serialised PointCloud2 of the hand cloud.
std::vector<std::uint8_t> ros1_message(const HandCloud& hand) {
  std::vector<std::uint8_t> m;
  const auto u32 = [&](std::uint32_t v) { m.insert(m.end(), reinterpret_cast<std::uint8_t*>(&v), reinterpret_cast<std::uint8_t*>(&v) + 4); };
  const auto text = [&](const std::string& s) {
    u32(std::uint32_t(s.size()));
    m.insert(m.end(), s.begin(), s.end());
  };
  u32(7);  // seq
  u32(100);
  u32(5);
  text("lidar");
  u32(hand.cloud.height);
  u32(hand.cloud.width);
  u32(std::uint32_t(hand.cloud.fields.size()));
  for (const PointField& f : hand.cloud.fields) {
    text(f.name);
    u32(f.offset);
    m.push_back(std::uint8_t(f.type));
    u32(f.count);
  }
  m.push_back(0);
  u32(hand.cloud.point_step);
  u32(hand.cloud.row_step);
  u32(std::uint32_t(hand.bytes.size()));
  m.insert(m.end(), hand.bytes.begin(), hand.bytes.end());
  m.push_back(1);
  return m;
}

TEST(PointCloud2, ARos1MessageIsParsedAndEveryCutIsRefused) {
  const HandCloud hand({{1, 2, 3}, {4, 5, 6}}, 2);
  std::vector<std::uint8_t> message = ros1_message(hand);
  const PointCloud2 cloud = parse_ros1_point_cloud2(message, "m");
  EXPECT_EQ(cloud.stamp_ns, 100000000005);
  EXPECT_EQ(cloud.frame_id, "lidar");
  EXPECT_EQ(cloud.fields.size(), 4u);
  EXPECT_EQ(cloud.fields[3].name, "ring");
  EXPECT_EQ(cloud.data.size(), hand.bytes.size());
  EXPECT_TRUE(cloud.is_dense);
  for (std::size_t cut = 0; cut + 1 < message.size(); ++cut) {  // the last byte, is_dense, may be left out
    try {
      (void)parse_ros1_point_cloud2(std::span<const std::uint8_t>(message).first(cut), "m");
      ADD_FAILURE() << "a message cut at byte " << cut << " was taken";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("m: byte "), std::string::npos) << e.what();
    }
  }
  message[12 + 9 + 8 + 4 + 5 + 4] = 9;  // x's datatype: after the stamp, frame_id, sizes, count, name, offset
  try {
    (void)parse_ros1_point_cloud2(message, "m");
    ADD_FAILURE() << "datatype 9 was taken";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "m: byte 42: field x: datatype 9 is not 1-8");
  }
}

}  // namespace
}  // namespace eco::io
