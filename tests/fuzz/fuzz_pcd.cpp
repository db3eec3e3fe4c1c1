// libFuzzer: any bytes given to the PCD parser end in a cloud or an eco::io::Error, nothing else.

#include <eco/io/pcd.hpp>

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)eco::io::parse_pcd(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.pcd");
  } catch (const eco::io::Error&) {
  }
  return 0;
}
