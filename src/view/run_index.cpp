// frames.csv, written a flushed line at a time and read back with a line number for what is wrong.

#include "view/run_index.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

namespace eco::view {

void write_index_row(std::FILE* index, const IndexRow& row) {
  const FrameFigures& f = row.figures;
  std::fprintf(index, "%u,%.6f,%.6f,%.6f,", row.frame, row.sensor.x(), row.sensor.y(), row.sensor.z());
  if (row.reference) {
    std::fprintf(index, "%.6f,%.6f,%.6f,", row.reference->x(), row.reference->y(), row.reference->z());
  } else {
    std::fprintf(index, ",,,");
  }
  const RegionExtents& r = f.region;
  std::fprintf(index, "%zu,%zu,%zu,%zu,%zu,%.4f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", f.scan, f.inserted, f.pruned,
               f.cleared, f.held, f.update_ms, r.radius, r.ahead, r.behind, r.left, r.right, r.up, r.down);
  std::fflush(index);
}

namespace {

/// The row a line makes; throws std::invalid_argument naming the field that is wrong.
IndexRow parse_row(const std::string& line) {
  static const char* const kFields[] = {"frame",         "x",            "y",           "z",            "ref_x",
                                        "ref_y",         "ref_z",        "scan",        "inserted",     "pruned",
                                        "cleared",       "held",         "update_ms",   "region_radius", "region_ahead",
                                        "region_behind", "region_left",  "region_right", "region_up",   "region_down"};
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  if (cells.size() != std::size(kFields)) {
    throw std::invalid_argument(std::to_string(cells.size()) + " fields, not " + std::to_string(std::size(kFields)));
  }
  const auto number = [&](std::size_t i) {
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(cells[i], &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != cells[i].size() || !std::isfinite(value)) {
      throw std::invalid_argument("field " + std::string(kFields[i]) + " is \"" + cells[i] + "\", not a number");
    }
    return value;
  };
  const auto count = [&](std::size_t i) {
    const double value = number(i);
    if (value < 0 || value != std::floor(value) || value > 4294967295.0) {
      throw std::invalid_argument("field " + std::string(kFields[i]) + " is \"" + cells[i] + "\", not a count");
    }
    return std::size_t(value);
  };
  IndexRow row;
  row.frame = std::uint32_t(count(0));
  row.sensor = {number(1), number(2), number(3)};
  if (!cells[4].empty() || !cells[5].empty() || !cells[6].empty()) row.reference = Eigen::Vector3d(number(4), number(5), number(6));
  row.figures = {count(7), count(8), count(9), count(10), count(11), number(12), {}};
  RegionExtents& r = row.figures.region;
  double* extents[] = {&r.radius, &r.ahead, &r.behind, &r.left, &r.right, &r.up, &r.down};
  for (std::size_t i = 0; i < std::size(extents); ++i) {
    *extents[i] = number(13 + i);
    if (*extents[i] < 0.0) throw std::invalid_argument("field " + std::string(kFields[13 + i]) + " is negative");
  }
  return row;
}

}  // namespace

Index read_index(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Index{{}, std::string(kIndexFile) + ": cannot be opened"};
  std::stringstream whole;
  whole << in.rdbuf();
  return parse_index(whole.str());
}

Index parse_index(std::string_view text) {
  Index index;
  std::size_t line_number = 0;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = text.find('\n', at);
    if (end == std::string::npos) break;  // still being written
    const std::string line(text.substr(at, end - at));
    at = end + 1;
    if (++line_number == 1) {
      if (line != kIndexHeader) {
        index.error = std::string(kIndexFile) + ", line 1: not the header \"" + kIndexHeader + "\"";
        return index;
      }
      continue;
    }
    try {
      index.rows.push_back(parse_row(line));
    } catch (const std::invalid_argument& e) {
      index.error = std::string(kIndexFile) + ", line " + std::to_string(line_number) + ": " + e.what();
      return index;
    }
  }
  return index;
}

}  // namespace eco::view
