// libFuzzer: any bytes as an MCAP file end in clouds read (or a recording refused) with an
// eco::io::Error, nothing else: every record, chunk (uncompressed, lz4, zstd) and message header.

#include "read_recording.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const FuzzFile file(".mcap");
  read_as_recording(data, size, file.path());
  return 0;
}
