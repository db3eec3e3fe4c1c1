#pragma once
// A recording's index, view/frames.csv: a line a recorded frame, the frame's file written before
// its line. The server reads it anew on each request, so a live run's new frames appear.

#include <eco/types.hpp>

#include <Eigen/Core>

#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace eco::view {

inline constexpr const char* kRunFile = "run.json";
inline constexpr const char* kIndexFile = "frames.csv";
inline constexpr const char* kIndexHeader =
    "frame,x,y,z,ref_x,ref_y,ref_z,scan,inserted,pruned,cleared,held,update_ms,"
    "region_radius,region_ahead,region_behind,region_left,region_right,region_up,region_down";

/// The figures the map reported for a frame (the page's panel and chart).
struct FrameFigures {
  std::size_t scan = 0, inserted = 0, pruned = 0, cleared = 0, held = 0;
  double update_ms = 0.0;
  RegionExtents region;  ///< the region the map held (Config::region as sized this frame); zeros: the cube
};

struct IndexRow {
  std::uint32_t frame = 0;
  Eigen::Vector3d sensor = Eigen::Vector3d::Zero();  ///< world frame
  std::optional<Eigen::Vector3d> reference;          ///< the reference path's position, if any
  FrameFigures figures;
};

/// Appends `row` to the open index and flushes it.
void write_index_row(std::FILE* index, const IndexRow& row);

struct Index {
  std::vector<IndexRow> rows;
  std::string error;  ///< empty, or what is wrong and on which line (the rows before it are kept)
};
/// The index at `path`. A last line without its newline is a row still being written: left out.
[[nodiscard]] Index read_index(const std::string& path);
/// The same of the file's text.
[[nodiscard]] Index parse_index(std::string_view text);

}  // namespace eco::view
