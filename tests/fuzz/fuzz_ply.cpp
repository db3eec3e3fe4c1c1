// libFuzzer: any bytes given to the PLY parser end in a cloud or an eco::io::Error, nothing else.

#include <eco/io/ply.hpp>

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)eco::io::parse_ply(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.ply");
  } catch (const eco::io::Error&) {
  }
  return 0;
}
