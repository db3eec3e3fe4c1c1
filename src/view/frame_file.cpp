// A frame's bytes: header, held points, their ages and attributes, dropped, cleared, voxels, CRC.

#include "view/frame_file.hpp"

#include "bytes/byte_stream.hpp"
#include "bytes/checksum.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

namespace eco::view {
namespace {

using detail::ByteError;
using detail::ByteReader;
using detail::ByteWriter;

constexpr std::string_view kMagic{"ECO view", 8};
constexpr std::uint32_t kVersion = 1;
constexpr std::uint32_t kHasIntensity = 1u << 0;
constexpr std::uint32_t kHasIds = 1u << 1;
constexpr double kSteps = 32767.0;  // int16's largest magnitude

/// `value` as a person reads it: 0.1, 1e+300.
std::string shortest(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

/// The sensor's voxel: voxel keys are stored as int16 offsets from it.
VoxelKey sensor_voxel(const Eigen::Isometry3d& pose, double voxel_size) {
  return voxel_of(pose.translation(), voxel_size);
}

std::int16_t voxel_offset(std::int64_t key, std::int64_t centre) {
  const std::int64_t d = key - centre;
  if (d < std::numeric_limits<std::int16_t>::min() || d > std::numeric_limits<std::int16_t>::max()) {
    throw std::invalid_argument("a voxel " + std::to_string(d) + " voxels from the sensor's does not fit a frame file");
  }
  return std::int16_t(d);
}

void put_floats(ByteWriter& out, const std::vector<Eigen::Vector3f>& points) {
  for (const Eigen::Vector3f& p : points) {
    out.put(p.x());
    out.put(p.y());
    out.put(p.z());
  }
}

std::vector<Eigen::Vector3f> get_floats(ByteReader& in, std::size_t n, const char* what) {
  std::vector<float> flat;
  in.get_values(flat, 3 * n, what);
  std::vector<Eigen::Vector3f> points(n);
  for (std::size_t i = 0; i < n; ++i) points[i] = {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
  return points;
}

FrameRecord decode_payload(ByteReader& in) {
  FrameRecord r;
  if (const auto version = in.get<std::uint32_t>("version"); version != kVersion) {
    ByteReader::fail_at(in.offset() - 4, "version " + std::to_string(version) + ", this viewer reads " +
                                             std::to_string(kVersion));
  }
  r.frame = in.get<std::uint32_t>("frame number");
  const auto flags = in.get<std::uint32_t>("flags");
  if (flags & ~(kHasIntensity | kHasIds)) in.fail("unknown flags " + std::to_string(flags));
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 4; ++col) r.world_T_sensor.matrix()(row, col) = in.get<double>("pose");
  }
  // bounds that keep every conversion below in range (a position in float, a voxel key in int64)
  if (!r.world_T_sensor.matrix().allFinite() || r.world_T_sensor.translation().cwiseAbs().maxCoeff() > 1e12) {
    ByteReader::fail_at(in.offset() - 96, "the pose is not finite or lies beyond 1e12 m");
  }
  const auto step = in.get<double>("quantum");
  if (!(step > 0.0 && step <= 100.0)) {
    ByteReader::fail_at(in.offset() - 8, "quantum " + shortest(step) + " m is not in (0, 100]");
  }
  r.voxel_size = in.get<double>("voxel size");
  if (!(r.voxel_size >= 1e-6 && r.voxel_size <= 1e6)) {
    ByteReader::fail_at(in.offset() - 8, "voxel size " + shortest(r.voxel_size) + " m is not in [1e-6, 1e6]");
  }
  const auto held = in.get<std::uint32_t>("held count");
  const auto dropped = in.get<std::uint32_t>("dropped count");
  const auto cleared = in.get<std::uint32_t>("cleared count");
  const auto voxels = in.get<std::uint32_t>("voxel count");

  std::vector<std::int16_t> q;
  in.get_values(q, 3 * std::size_t(held), "held points");
  r.held.resize(held);
  r.step = step;
  for (std::size_t i = 0; i < held; ++i) {
    r.held[i] = (Eigen::Vector3d(q[3 * i], q[3 * i + 1], q[3 * i + 2]) * step).cast<float>();
  }
  in.get_values(r.age, held, "ages");
  if (flags & kHasIntensity) in.get_values(r.intensity, held, "intensities");
  if (flags & kHasIds) in.get_values(r.id, held, "ids");
  r.dropped = get_floats(in, dropped, "dropped points");
  r.cleared = get_floats(in, cleared, "cleared points");
  std::vector<std::int16_t> v;
  in.get_values(v, 3 * std::size_t(voxels), "voxels");
  const VoxelKey centre = sensor_voxel(r.world_T_sensor, r.voxel_size);
  r.voxels.resize(voxels);
  for (std::size_t i = 0; i < voxels; ++i) {
    r.voxels[i] = {centre.x + v[3 * i], centre.y + v[3 * i + 1], centre.z + v[3 * i + 2]};
  }
  return r;
}

}  // namespace

std::string encode_frame(const FrameRecord& r) {
  const std::size_t n = r.held.size();
  if (r.age.size() != n || (!r.intensity.empty() && r.intensity.size() != n) || (!r.id.empty() && r.id.size() != n)) {
    throw std::invalid_argument("a frame's ages and attributes must be one per held point");
  }
  if (!(r.voxel_size > 0.0)) throw std::invalid_argument("voxel size " + std::to_string(r.voxel_size) + " is not positive");
  ByteWriter out;
  out.put_bytes(kMagic);
  out.put(kVersion);
  out.put(r.frame);
  out.put(std::uint32_t((r.intensity.empty() ? 0 : kHasIntensity) | (r.id.empty() ? 0 : kHasIds)));
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 4; ++col) out.put(r.world_T_sensor.matrix()(row, col));
  }
  const double step = position_step(r.held);
  out.put(step);
  out.put(r.voxel_size);
  for (const std::size_t count : {n, r.dropped.size(), r.cleared.size(), r.voxels.size()}) out.put(std::uint32_t(count));
  for (const Eigen::Vector3f& p : r.held) {
    for (int axis = 0; axis < 3; ++axis) out.put(in_steps(p[axis], step));
  }
  for (const std::uint16_t a : r.age) out.put(a);
  for (const float i : r.intensity) out.put(i);
  for (const std::uint32_t i : r.id) out.put(i);
  put_floats(out, r.dropped);
  put_floats(out, r.cleared);
  const VoxelKey centre = sensor_voxel(r.world_T_sensor, r.voxel_size);
  for (const VoxelKey& k : r.voxels) {
    out.put(voxel_offset(k.x, centre.x));
    out.put(voxel_offset(k.y, centre.y));
    out.put(voxel_offset(k.z, centre.z));
  }
  out.put(detail::checksum(out.bytes()));
  return std::move(out.bytes());
}

FrameRecord decode_frame(std::string_view bytes, const std::string& name) {
  const auto refuse = [&](std::size_t at, const std::string& what) {
    return FrameFileError(name + ": byte " + std::to_string(at) + ": " + what);
  };
  if (bytes.size() < kMagic.size() + 4 || bytes.substr(0, kMagic.size()) != kMagic) {
    throw refuse(0, "not a frame file of eco's viewer (no \"ECO view\" magic)");
  }
  const std::string_view payload = bytes.substr(0, bytes.size() - 4);
  try {
    ByteReader in(payload, kMagic.size());
    FrameRecord r = decode_payload(in);
    if (in.left() != 0) in.fail(std::to_string(in.left()) + " bytes after the frame's last part");
    const auto stored = ByteReader(bytes, payload.size()).get<std::uint32_t>("checksum");
    if (stored != detail::checksum(payload)) ByteReader::fail_at(payload.size(), "checksum mismatch: the file is damaged");
    return r;
  } catch (const ByteError& e) {
    throw refuse(e.offset, e.what());
  }
}

void write_frame_file(const std::string& path, const FrameRecord& record) {
  const std::string bytes = encode_frame(record);
  const std::string partial = path + ".partial";
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    if (!out.flush()) throw std::runtime_error(partial + ": cannot write the frame");
  }
  std::error_code error;
  std::filesystem::rename(partial, path, error);
  if (error) throw std::runtime_error(path + ": " + error.message());
}

FrameRecord read_frame_file(const std::string& path) {
  const std::string name = std::filesystem::path(path).filename().string();
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw FrameFileError(name + ": cannot be opened");
  std::string bytes(std::size_t(in.tellg()), '\0');
  in.seekg(0);
  if (!in.read(bytes.data(), std::streamsize(bytes.size()))) throw FrameFileError(name + ": cannot be read");
  return decode_frame(bytes, name);
}

double position_step(const std::vector<Eigen::Vector3f>& held) {
  float extent = 0.0f;
  for (const Eigen::Vector3f& p : held) extent = std::max(extent, p.cwiseAbs().maxCoeff());
  return extent > 0.0f ? double(extent) / kSteps : 1.0;
}

std::string frame_file_name(std::uint32_t frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06u.bin", frame);
  return name;
}

}  // namespace eco::view
