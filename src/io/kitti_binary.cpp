// KITTI's binary files: scans (16-byte records) and SemanticKITTI labels (4-byte records).

#include <eco/io/kitti.hpp>

#include "io/files.hpp"
#include "io/records.hpp"

#include <bit>
#include <cstring>

namespace eco::io {

static_assert(std::endian::native == std::endian::little, "KITTI files are little-endian");

namespace {

constexpr std::size_t kScanRecord = 4 * sizeof(float);

void check_record_size(std::string_view bytes, std::size_t record, const std::string& source,
                       const char* what) {
  if (bytes.empty()) throw Error(source, "", std::string("is empty: a ") + what + " file holds at least one record");
  if (bytes.size() % record != 0) {
    throw Error(source, at_byte(bytes.size() - bytes.size() % record),
                "size " + std::to_string(bytes.size()) + " is not a multiple of " +
                    std::to_string(record) + " bytes: a " + what + " file ends in a partial record");
  }
}

}  // namespace

PointCloud parse_kitti_scan(std::string_view bytes, const std::string& source) {
  check_record_size(bytes, kScanRecord, source, "KITTI scan");
  const std::size_t n = bytes.size() / kScanRecord;
  PointCloud cloud;
  cloud.points.resize(n);
  cloud.intensity.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    float record[4];
    std::memcpy(record, bytes.data() + i * kScanRecord, kScanRecord);
    cloud.points[i] = {record[0], record[1], record[2]};
    cloud.intensity[i] = record[3];
  }
  return cloud;
}

PointCloud read_kitti_scan(const std::filesystem::path& path) {
  return parse_kitti_scan(detail::read_file(path), path.string());
}

void write_kitti_scan(const std::filesystem::path& path, const PointCloud& cloud) {
  if (cloud.size() == 0) throw Error(path.string(), "", "a KITTI scan holds at least one point");
  detail::check_writable(cloud, path.string());
  std::string bytes(cloud.size() * kScanRecord, '\0');
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const float record[4] = {cloud.points[i].x(), cloud.points[i].y(), cloud.points[i].z(),
                             cloud.has_intensity() ? cloud.intensity[i] : 0.0f};
    std::memcpy(bytes.data() + i * kScanRecord, record, kScanRecord);
  }
  detail::write_file(path, bytes);
}

std::vector<std::uint32_t> parse_kitti_labels(std::string_view bytes, const std::string& source) {
  check_record_size(bytes, sizeof(std::uint32_t), source, "label");
  std::vector<std::uint32_t> labels(bytes.size() / sizeof(std::uint32_t));
  std::memcpy(labels.data(), bytes.data(), bytes.size());
  return labels;
}

std::vector<std::uint32_t> read_kitti_labels(const std::filesystem::path& path) {
  return parse_kitti_labels(detail::read_file(path), path.string());
}

void write_kitti_labels(const std::filesystem::path& path, std::span<const std::uint32_t> labels) {
  detail::write_file(path, std::string_view(reinterpret_cast<const char*>(labels.data()),
                                            labels.size_bytes()));
}

}  // namespace eco::io
