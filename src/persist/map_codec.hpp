#pragma once
// A map as the bytes of a map file (docs/map-format.md) and back: the configuration, the frame's
// motion, the tree's nodes and points, and free-space clearing's state while it is on.

#include "clearing/clearing.hpp"
#include "core/tree/tree.hpp"

#include <memory>
#include <string>
#include <string_view>

namespace eco::detail {

/// The versions this library writes and reads: 1 for a map that holds the cube, 2 (the region's
/// fields after the configuration's) for a map that holds another region.
inline constexpr std::uint32_t kMapFileVersion = 1;
inline constexpr std::uint32_t kMapFileVersionWithRegion = 2;
/// A region with its lookahead, budget and the size they gave it (written for every region since).
inline constexpr std::uint32_t kMapFileVersionSizedRegion = 3;

/// The file's bytes for `tree` and, while clearing is on, its `clearing` state.
std::string encode_map(const Tree& tree, const ClearingState* clearing);

struct DecodedMap {
  std::unique_ptr<Tree> tree;
  std::unique_ptr<ClearingState> clearing;  ///< null while clearing is off
};
/// The map in `bytes`. Throws ByteError (bytes/byte_stream.hpp) naming the first byte that does
/// not make a map: a wrong magic or version, a checksum that does not match, a truncated
/// section, a value out of range, a tree whose parts do not fit together.
DecodedMap decode_map(std::string_view bytes);

}  // namespace eco::detail
