// libFuzzer: any bytes given to the viewer's frame decoder end in a frame or a FrameFileError
// naming the file and a byte, nothing else; a frame it reads is sent to the page at any budget and
// written again to the same frame. Inputs whose first byte is even get their checksum set right
// first, so that the fuzzer reaches the parts behind it.

#include "bytes/checksum.hpp"
#include "view/display_frame.hpp"
#include "view/frame_file.hpp"

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  if (size >= 16 && data[0] % 2 == 0) {
    bytes[0] = 'E';  // the magic's first byte, which the choice above took
    const std::uint32_t crc = eco::detail::checksum(std::string_view(bytes).substr(0, size - 4));
    std::memcpy(bytes.data() + size - 4, &crc, 4);
  }
  eco::view::FrameRecord frame;
  try {
    frame = eco::view::decode_frame(bytes, "fuzz.bin");
  } catch (const eco::view::FrameFileError& e) {
    if (std::strncmp(e.what(), "fuzz.bin: byte ", 15) != 0) __builtin_trap();
    return 0;
  }
  (void)eco::view::display_bytes(frame, size % 7, size % 2 == 0);
  try {
    const eco::view::FrameRecord again = eco::view::decode_frame(eco::view::encode_frame(frame), "again.bin");
    if (again.held.size() != frame.held.size() || again.age != frame.age || again.voxels != frame.voxels) __builtin_trap();
  } catch (const std::invalid_argument&) {  // a voxel key out of int16's reach from a pose changed by rounding
  }
  return 0;
}
