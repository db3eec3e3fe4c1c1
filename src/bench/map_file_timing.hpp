#pragma once
// What a map file costs (EgoOctree::save and EgoOctree::load), against the floor of any such
// file: writing the same bytes and reading them back raw.

#include <eco/ego_octree.hpp>

#include <cstddef>

namespace eco::bench {

struct MapFileTiming {
  double save_ms = 0.0;    ///< EgoOctree::save, flushed to the disk
  double load_ms = 0.0;    ///< EgoOctree::load
  double raw_ms = 0.0;     ///< the same bytes written, flushed and read back with plain calls
  std::size_t file_bytes = 0;
  std::size_t point_bytes = 0;  ///< the held points' coordinates and kept attributes (12 + 4 a column)
};

/// Saves `tree` to a file in the system's temporary folder and loads it back, then writes and
/// reads the same bytes raw; each the best of `rounds`. The file is removed.
[[nodiscard]] MapFileTiming time_map_file(const EgoOctree& tree, int rounds = 3);

}  // namespace eco::bench
