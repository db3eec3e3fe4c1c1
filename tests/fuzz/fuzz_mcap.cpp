// libFuzzer: any bytes as an MCAP file end in clouds read (or a recording refused) with an
// eco::io::Error, nothing else: every record, chunk (uncompressed, lz4, zstd) and message header.

#include <eco/io/error.hpp>
#include <eco/io/recording.hpp>

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/eco-fuzz-" + std::to_string(getpid()) + ".mcap";
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  try {
    eco::io::Recording bag(path, {});
    for (std::size_t i = 0; i < bag.size(); ++i) (void)bag.read(i);
  } catch (const eco::io::Error&) {
  }
  return 0;
}
