#pragma once
// The CRC-32 that closes a map file and a viewer's frame file: zlib's (the ISO-HDLC polynomial,
// reflected), computed by Intel's ISA-L, which folds it with carry-less multiplies at memory
// speed (zlib's own loop ran at a third of it, and a map's load reads every byte for it).

#include <cstdint>
#include <string_view>

namespace eco::detail {

std::uint32_t checksum(std::string_view bytes);

}  // namespace eco::detail
