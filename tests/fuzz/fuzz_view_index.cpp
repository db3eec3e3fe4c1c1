// libFuzzer: any text given as the viewer's frames.csv ends in rows and, where a line is wrong,
// an error naming it; never a crash, never a row past the error.

#include "view/run_index.hpp"

#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const eco::view::Index index = eco::view::parse_index(std::string_view(reinterpret_cast<const char*>(data), size));
  if (!index.error.empty() && index.error.rfind("frames.csv, line ", 0) != 0) __builtin_trap();
  return 0;
}
