#pragma once
// One recorded frame of a run, as the viewer reads it: the held points (quantised about the
// sensor), each point's age, the points this frame dropped at the box's faces and cleared, and the
// voxel map. The byte layout is docs/view-format.md's; a file that does not make a frame is
// refused with its name and the byte offset of the first part that is wrong.

#include <eco/types.hpp>

#include <Eigen/Geometry>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace eco::view {

struct FrameRecord {
  std::uint32_t frame = 0;
  Eigen::Isometry3d world_T_sensor = Eigen::Isometry3d::Identity();
  double voxel_size = 0.1;  ///< [m] of `voxels`
  /// Held points minus the sensor position [m]; stored as int16 steps of position_step(held).
  std::vector<Eigen::Vector3f> held;
  double step = 0.0;  ///< the step `held` was read in (0 until read: encode_frame finds its own)
  std::vector<std::uint16_t> age;  ///< frames since each held point came in (0: inserted this frame)
  std::vector<float> intensity;    ///< empty, or one per held point
  std::vector<std::uint32_t> id;   ///< empty, or one per held point
  std::vector<Eigen::Vector3f> dropped;  ///< left the box this frame, minus the sensor position
  std::vector<Eigen::Vector3f> cleared;  ///< seen through this frame, minus the sensor position
  std::vector<VoxelKey> voxels;          ///< occupied voxels (world keys at voxel_size)
};

/// Thrown for bytes that do not make a frame: the message names the file and the byte offset.
struct FrameFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The frame as bytes: held coordinates to within 1/65534 of their largest extent (0.3 mm in a 20 m
/// box), everything else as given, then a CRC-32 of all that precedes it.
[[nodiscard]] std::string encode_frame(const FrameRecord& record);
/// The frame those bytes make; `name` (the file's) goes into any error.
[[nodiscard]] FrameRecord decode_frame(std::string_view bytes, const std::string& name);

/// Writes `record` to `path` whole (beside it, then renamed), so a reader never sees half a file.
void write_frame_file(const std::string& path, const FrameRecord& record);
/// Throws FrameFileError naming `path` when it cannot be read or does not make a frame.
[[nodiscard]] FrameRecord read_frame_file(const std::string& path);

/// The int16 step both the file and the page use for `held`: the largest extent / 32767.
[[nodiscard]] double position_step(const std::vector<Eigen::Vector3f>& held);
/// `value` / `step` rounded to the nearest int16 step (`value` within 32767 steps).
[[nodiscard]] inline std::int16_t in_steps(float value, double step) {
  const double steps = double(value) / step;
  return std::int16_t(steps >= 0.0 ? steps + 0.5 : steps - 0.5);
}

/// "frame_000042.bin": the name a frame's file has in a recording.
[[nodiscard]] std::string frame_file_name(std::uint32_t frame);

}  // namespace eco::view
