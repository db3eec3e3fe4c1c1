#pragma once
// The CRC-32 (zlib's) that closes a map file and a viewer's frame file.

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <string_view>

namespace eco::detail {

inline std::uint32_t checksum(std::string_view bytes) {
  uLong crc = crc32(0L, Z_NULL, 0);
  // zlib takes at most 4 GB a call
  for (std::size_t at = 0; at < bytes.size(); at += std::size_t{1} << 30) {
    const std::size_t n = std::min(bytes.size() - at, std::size_t{1} << 30);
    crc = crc32(crc, reinterpret_cast<const Bytef*>(bytes.data() + at), uInt(n));
  }
  return std::uint32_t(crc);
}

}  // namespace eco::detail
