// libFuzzer: any bytes given to the KITTI scan and label parsers end in records or an
// eco::io::Error, nothing else.

#include <eco/io/kitti.hpp>

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    (void)eco::io::parse_kitti_scan(bytes, "fuzz.bin");
  } catch (const eco::io::Error&) {
  }
  try {
    (void)eco::io::parse_kitti_labels(bytes, "fuzz.label");
  } catch (const eco::io::Error&) {
  }
  return 0;
}
