// libFuzzer: any bytes as a ROS 1 bag end in clouds read (or the bag refused) with an
// eco::io::Error, nothing else. ECO checks the records' framing, then Debian's rosbag_storage
// parses them (not instrumented): what is fuzzed is that check, that every failure of rosbag's
// comes out as a clear error, and ECO's reading of what it hands over.

#include "read_recording.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const FuzzFile file(".bag");
  read_as_recording(data, size, file.path());
  return 0;
}
