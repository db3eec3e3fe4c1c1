// The recorder: births of held points carried from frame to frame, removals sorted by where they
// went, the frame written whole before its line in frames.csv names it.

#include "view/recorder.hpp"


#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <unordered_set>

namespace eco::view {

Recorder::Recorder(const std::string& folder, const RunInfo& info) : folder_(folder), info_(info) {
  namespace fs = std::filesystem;
  fs::create_directories(folder_);
  for (const fs::directory_entry& entry : fs::directory_iterator(folder_)) {
    if (entry.path().extension() == ".bin") fs::remove(entry.path());  // an earlier recording's frames
  }
  const char* shapes[] = {"cube", "ball", "oriented_box"};
  const nlohmann::json run{{"title", info.title},
                           {"box_side", info.box_side},
                           {"region", shapes[int(info.region)]},
                           {"turn_with", info.turn_with == TurnWith::Full ? "full" : "yaw"},
                           {"voxel_size", info.voxel_size},
                           {"frames", info.frames},
                           {"has_reference", info.has_reference}};
  std::ofstream(fs::path(folder_) / kRunFile) << run.dump(2) << '\n';
  index_ = std::fopen((fs::path(folder_) / kIndexFile).c_str(), "w");
  if (!index_) throw std::runtime_error(folder_ + "/" + std::string(kIndexFile) + ": cannot be written");
  std::fprintf(index_, "%s\n", kIndexHeader);
  std::fflush(index_);
}

Recorder::~Recorder() {
  if (index_) std::fclose(index_);
}

void Recorder::carry(std::uint32_t frame, const std::vector<HeldPoint>& held) {
  for (const HeldPoint& p : held) {
    BirthTable::Entry& b = births_.at(p.point, frame);
    if (b.now < std::numeric_limits<std::uint16_t>::max()) ++b.now;
  }
  births_.end_frame([](const BirthTable::Entry&) {});
}

FrameChanges Recorder::record(std::uint32_t frame, const Eigen::Isometry3d& world_T_sensor,
                              const std::vector<HeldPoint>& held, const std::vector<VoxelKey>& voxels,
                              FrameFigures figures, const std::optional<Eigen::Vector3d>& reference) {
  const Eigen::Vector3d sensor = world_T_sensor.translation();
  FrameRecord r;
  r.frame = frame;
  r.world_T_sensor = world_T_sensor;
  r.voxel_size = info_.voxel_size;
  r.voxels = voxels;
  r.held.reserve(held.size());
  r.age.reserve(held.size());
  const bool ids = std::any_of(held.begin(), held.end(), [](const HeldPoint& p) { return p.attributes.id != 0; });
  const bool intensities =
      std::any_of(held.begin(), held.end(), [](const HeldPoint& p) { return p.attributes.intensity != 0.0f; });
  FrameChanges changes;
  for (const HeldPoint& p : held) {
    BirthTable::Entry& b = births_.at(p.point, frame);
    if (b.now < std::numeric_limits<std::uint16_t>::max()) ++b.now;
    if (b.now > b.before) ++changes.inserted;  // more here than the last frame held
    r.held.push_back((p.point - sensor).cast<float>());
    r.age.push_back(std::uint16_t(std::min<std::uint32_t>(frame - b.frame, std::numeric_limits<std::uint16_t>::max())));
    if (intensities) r.intensity.push_back(p.attributes.intensity);
    if (ids) r.id.push_back(p.attributes.id);
  }
  // what the last frame held and this one does not: outside the new box it was dropped, inside cleared
  const Eigen::Array3d lo = sensor.array() - info_.box_side / 2, hi = sensor.array() + info_.box_side / 2;
  births_.end_frame([&](const BirthTable::Entry& b) {
    if (b.now >= b.before) return;
    const Eigen::Vector3d p(b.x, b.y, b.z);
    const bool in_box = info_.box_side > 0.0 && (p.array() >= lo).all() && (p.array() < hi).all();
    std::vector<Eigen::Vector3f>& list = in_box ? r.cleared : r.dropped;
    list.insert(list.end(), b.before - b.now, (p - sensor).cast<float>());
  });
  changes.dropped = r.dropped.size();
  changes.cleared = r.cleared.size();
  if (!info_.map_counts) {
    figures.inserted = changes.inserted;
    figures.pruned = changes.dropped;
    figures.cleared = changes.cleared;
  }

  write_frame_file((std::filesystem::path(folder_) / frame_file_name(frame)).string(), r);
  write_index_row(index_, IndexRow{frame, sensor, reference, figures});
  return changes;
}

std::vector<VoxelKey> occupied_voxels(const std::vector<HeldPoint>& held, double voxel_size) {
  std::unordered_set<VoxelKey> voxels;
  for (const HeldPoint& p : held) voxels.insert(voxel_of(p.point, voxel_size));
  return {voxels.begin(), voxels.end()};
}

}  // namespace eco::view
