// Thinning and packing a frame for the page.

#include "view/display_frame.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>

namespace eco::view {
namespace {

template <class T>
void put(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

/// Every `stride`-th of `points`.
void put_points(std::string& out, const std::vector<Eigen::Vector3f>& points, std::size_t stride) {
  for (std::size_t i = 0; i < points.size(); i += stride) {
    for (int axis = 0; axis < 3; ++axis) put(out, points[i][axis]);
  }
}

std::size_t thinned(std::size_t count, std::size_t stride) { return (count + stride - 1) / stride; }

/// The sensor's rotation, row by row: the page turns the region with it.
nlohmann::json turn_of(const Eigen::Isometry3d& world_T_sensor) {
  nlohmann::json rows = nlohmann::json::array();
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) rows.push_back(world_T_sensor.linear()(row, col));
  }
  return rows;
}

}  // namespace

std::size_t thinning_stride(std::size_t count, std::size_t budget) {
  return budget == 0 || count <= budget ? 1 : (count + budget - 1) / budget;
}

std::string display_bytes(const FrameRecord& r, std::size_t budget, bool with_voxels) {
  const std::size_t stride = thinning_stride(r.held.size(), budget);
  const std::size_t voxel_stride = thinning_stride(r.voxels.size(), budget);
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < r.held.size(); i += stride) kept.push_back(i);
  std::vector<Eigen::Vector3f> voxels;
  const Eigen::Vector3d sensor = r.world_T_sensor.translation();
  for (std::size_t i = 0; with_voxels && i < r.voxels.size(); i += voxel_stride) {
    const VoxelKey& k = r.voxels[i];
    voxels.push_back(((Eigen::Vector3d(double(k.x), double(k.y), double(k.z)).array() + 0.5) * r.voxel_size -
                      sensor.array()).matrix().cast<float>());
  }
  const double step = r.step > 0.0 ? r.step : position_step(r.held);
  const nlohmann::json header{
      {"frame", r.frame},          {"sensor", {sensor.x(), sensor.y(), sensor.z()}},
      {"turn", turn_of(r.world_T_sensor)},
      {"held", r.held.size()},     {"drawn", kept.size()},
      {"stride", stride},          {"step", step},
      {"has_intensity", !r.intensity.empty()}, {"has_ids", !r.id.empty()},
      {"dropped", r.dropped.size()}, {"cleared", r.cleared.size()},
      {"dropped_drawn", thinned(r.dropped.size(), stride)}, {"cleared_drawn", thinned(r.cleared.size(), stride)},
      {"voxels", r.voxels.size()}, {"voxels_drawn", voxels.size()},
      {"voxel_stride", voxel_stride}, {"voxel_size", r.voxel_size}};
  std::string json = header.dump();
  json.resize((json.size() + 3) / 4 * 4, ' ');
  std::string out;
  out.reserve(4 + json.size() + 16 * kept.size() + 12 * (r.dropped.size() + r.cleared.size() + voxels.size()));
  put(out, std::uint32_t(json.size()));
  out += json;
  for (const std::size_t i : kept) {
    for (int axis = 0; axis < 3; ++axis) put(out, in_steps(r.held[i][axis], step));
  }
  for (const std::size_t i : kept) put(out, r.age[i]);
  if (!r.intensity.empty()) {
    for (const std::size_t i : kept) put(out, r.intensity[i]);
  }
  if (!r.id.empty()) {
    for (const std::size_t i : kept) put(out, r.id[i]);
  }
  put_points(out, r.dropped, stride);
  put_points(out, r.cleared, stride);
  put_points(out, voxels, 1);
  return out;
}

}  // namespace eco::view
