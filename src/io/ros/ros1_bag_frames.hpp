#pragma once
// The framing of a ROS 1 bag (format 2.0), checked before Debian's rosbag_storage reads it: every
// record's header and data within the file, a chunk's uncompressed size within reason, an index's
// entries within its data. rosbag allocates what a record declares and reads past what it holds,
// so a damaged bag is refused here, naming the byte, rather than by an allocation of gigabytes.

#include <filesystem>

namespace eco::io::detail {

/// Throws eco::io::Error naming `file` and the byte of the first record that does not hold
/// together, or of the end where a bag cut short stops.
void check_ros1_bag_frames(const std::filesystem::path& file);

}  // namespace eco::io::detail
