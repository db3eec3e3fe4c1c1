// libFuzzer: any bytes given to the map file's loader end in a tree or a ByteError, nothing else;
// a tree it loads answers queries and takes another frame (or refuses the frame by name). Inputs whose first byte is even get
// their checksum set right first, so that the fuzzer reaches the sections behind it.

#include "bytes/byte_stream.hpp"
#include "fuzz_file.hpp"
#include "persist/map_codec.hpp"

#include <eco/ego_octree.hpp>

#include <zlib.h>

#include <cstddef>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  if (size >= 24 && data[0] % 2 == 0) {
    bytes[0] = 'E';  // the magic's first byte, which the choice above took
    const auto crc = std::uint32_t(crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), uInt(size - 4)));
    std::memcpy(bytes.data() + size - 4, &crc, 4);
  }
  try {
    (void)eco::detail::decode_map(bytes);
  } catch (const eco::detail::ByteError&) {
    return 0;
  }
  // it makes a map: loaded through the public API, the tree answers and goes on
  static const FuzzFile scratch(".eco");
  std::FILE* file = std::fopen(scratch.path().c_str(), "wb");
  if (file == nullptr) return 0;
  std::fwrite(bytes.data(), 1, bytes.size(), file);
  std::fclose(file);
  eco::EgoOctree tree = eco::EgoOctree::load(scratch.path());
  (void)tree.knn(tree.pose().translation(), 5);
  (void)tree.voxel_keys(0.5);
  const std::vector<Eigen::Vector3f> scan{{1, 2, 0}, {-3, 0.5f, 1}, {0, 0, 0}};
  try {
    tree.update(tree.pose() * Eigen::Translation3d(0.5, 0, 0), scan);
  } catch (const std::invalid_argument&) {  // a scan the configuration cannot take (ids, times)
  }
  return 0;
}
