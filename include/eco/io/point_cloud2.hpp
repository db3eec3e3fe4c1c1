#pragma once
/// @file point_cloud2.hpp
/// sensor_msgs/PointCloud2 as LiDAR drivers write it: parsed from a ROS 1 message or a ROS 2
/// (CDR) one, then decoded into a scan with per-point times.
///
/// Drivers differ in where they put a point's time (Ouster `t` uint32 ns, Velodyne `time`
/// float32 s, Hesai and Robosense `timestamp` float64 s since the epoch, Livox `offset_time`
/// uint32 ns): CloudDecoder finds the field by name, its unit by type and whether it counts from
/// the header stamp or is absolute from its values, once, from the first cloud it sees.

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace eco::io {

/// sensor_msgs/PointField's datatypes.
enum class FieldType : std::uint8_t { Int8 = 1, UInt8 = 2, Int16 = 3, UInt16 = 4, Int32 = 5, UInt32 = 6, Float32 = 7, Float64 = 8 };

struct PointField {
  std::string name;
  std::uint32_t offset = 0;
  FieldType type = FieldType::Float32;
  std::uint32_t count = 1;
};

/// A PointCloud2 message; `data` views the bytes it was parsed from.
struct PointCloud2 {
  std::int64_t stamp_ns = 0;  ///< header stamp, nanoseconds
  std::string frame_id;
  std::uint32_t height = 0, width = 0;
  std::vector<PointField> fields;
  bool is_bigendian = false;
  std::uint32_t point_step = 0, row_step = 0;
  std::span<const std::uint8_t> data;
  bool is_dense = false;
};

/// Parses a ROS 1 serialised message. Throws eco::io::Error naming `source` and the byte where
/// the message stops making sense.
[[nodiscard]] PointCloud2 parse_ros1_point_cloud2(std::span<const std::uint8_t> message, const std::string& source);
/// Parses a ROS 2 CDR message (its 4-byte encapsulation header first, little or big endian).
[[nodiscard]] PointCloud2 parse_cdr_point_cloud2(std::span<const std::uint8_t> message, const std::string& source);

enum class TimeUnit { Auto, Seconds, Milliseconds, Microseconds, Nanoseconds };
/// "s", "ms", "us", "ns" or "auto"; nullopt for anything else.
[[nodiscard]] std::optional<TimeUnit> time_unit_named(const std::string& name);
[[nodiscard]] const char* name_of(TimeUnit unit);

struct TimeOptions {
  std::string field;               ///< empty: the first of t, time, timestamp, timestamps, offset_time, stamps
  TimeUnit unit = TimeUnit::Auto;  ///< Auto: integers are nanoseconds, floats seconds
};

/// A cloud as a scan: the points that are finite and not at the origin, in the cloud's frame.
struct DecodedCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<float> intensities;  ///< one per point, or empty without intensity/reflectivity
  std::vector<double> times;       ///< [s] after the header stamp, one per point, or empty without times
  std::size_t skipped_not_finite = 0, skipped_zero = 0;
};

/// How a recording's clouds are read: found from its first cloud, then kept for every other.
struct CloudLayout {
  std::string intensity_field;  ///< empty: none
  std::string time_field;       ///< empty: none
  TimeUnit time_unit = TimeUnit::Auto;
  bool absolute_times = false;  ///< the times are clock readings, not offsets from the stamp
  /// "time: field t (uint32) in ns after the header stamp; intensity: reflectivity"
  [[nodiscard]] std::string describe() const;
};

class CloudDecoder {
 public:
  explicit CloudDecoder(TimeOptions options = {}) : options_(std::move(options)) {}

  /// Decodes `cloud`; the first call fixes the layout. Throws eco::io::Error naming `source` for
  /// a cloud without x/y/z, fields beyond point_step, data shorter than height × row_step, a
  /// big-endian cloud, or a time field asked for and missing.
  [[nodiscard]] DecodedCloud decode(const PointCloud2& cloud, const std::string& source);
  /// The layout found (after the first decode).
  [[nodiscard]] const std::optional<CloudLayout>& layout() const { return layout_; }

 private:
  TimeOptions options_;
  std::optional<CloudLayout> layout_;
};

}  // namespace eco::io
