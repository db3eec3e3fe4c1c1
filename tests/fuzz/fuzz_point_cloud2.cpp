// libFuzzer: any bytes as a PointCloud2 message, in ROS 1's encoding and in CDR, end in a decoded
// scan or an eco::io::Error, nothing else: fields at any offset and of any type, steps and sizes
// that disagree, organised clouds.

#include <eco/io/error.hpp>
#include <eco/io/point_cloud2.hpp>

#include <cstddef>
#include <cstdint>
#include <span>

namespace {

void decode(const eco::io::PointCloud2& cloud) {
  eco::io::CloudDecoder decoder;
  (void)decoder.decode(cloud, "fuzz");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  try {
    decode(eco::io::parse_cdr_point_cloud2(bytes, "fuzz.cdr"));
  } catch (const eco::io::Error&) {
  }
  try {
    decode(eco::io::parse_ros1_point_cloud2(bytes, "fuzz.ros1"));
  } catch (const eco::io::Error&) {
  }
  return 0;
}
