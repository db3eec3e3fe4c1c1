#include "bytes/checksum.hpp"

#include <isa-l/crc.h>

namespace eco::detail {

std::uint32_t checksum(std::string_view bytes) {
  return crc32_gzip_refl(0, reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size());
}

}  // namespace eco::detail
