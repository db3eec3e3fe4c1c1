#include "clearing/sensor_frame.hpp"

#include "core/geometry/vector_clones.hpp"

namespace eco::detail {

SensorPose::SensorPose(const Eigen::Matrix3d& sensor_R_world, const Eigen::Vector3d& from_anchor)
    : matrix_(sensor_R_world), offset_(from_anchor) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) rotation[std::size_t(r)][std::size_t(c)] = sensor_R_world(r, c);
    offset[std::size_t(r)] = from_anchor[r];
  }
}

namespace {

/// A full group of packed points, for the compiler to load three at a time with shuffles.
ECO_WIDE_VECTOR_CLONES
void load_packed_group(const float* data, PixelLookup::Group& out) {
  for (std::size_t i = 0; i < PixelLookup::kGroup; ++i) {
    out.x[i] = data[3 * i], out.y[i] = data[3 * i + 1], out.z[i] = data[3 * i + 2];
  }
}

}  // namespace

void load_returns(const float* data, std::size_t stride, std::size_t n, PixelLookup::Group& out) {
  out.size = n;
  if (stride == 3 && n == PixelLookup::kGroup) return load_packed_group(data, out);
  for (std::size_t i = 0; i < n; ++i, data += stride) out.x[i] = data[0], out.y[i] = data[1], out.z[i] = data[2];
}

ECO_WIDE_VECTOR_CLONES
void to_sensor_frame(const SensorPose& pose, const StoredGroup& in, PixelLookup::Group& out) {
  const auto r = pose.rotation;  // copies: the output's doubles could alias the pose's, for all GCC knows
  const auto o = pose.offset;
  for (std::size_t i = 0; i < PixelLookup::kGroup; ++i) {
    const double x = o[0] + double(in.x[i]), y = o[1] + double(in.y[i]), z = o[2] + double(in.z[i]);
    out.x[i] = (r[0][0] * x + r[0][1] * y) + r[0][2] * z;
    out.y[i] = (r[1][0] * x + r[1][1] * y) + r[1][2] * z;
    out.z[i] = r[2][0] * x + (r[2][1] * y + r[2][2] * z);
  }
  out.size = in.size;
}

}  // namespace eco::detail
