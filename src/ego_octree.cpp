// EgoOctree: construction, accessors, iteration and statistics. The update is in update/, the
// queries in query/.

#include "clearing/clearing.hpp"
#include "core/invariants.hpp"
#include "core/tree.hpp"
#include "persist/byte_stream.hpp"
#include "persist/map_codec.hpp"
#include "persist/map_file.hpp"
#include "query/frames.hpp"
#include "query/queries.hpp"
#include "update/stages.hpp"

#include <eco/ego_octree.hpp>

namespace eco {

EgoOctree::EgoOctree(const Config& config)
    : tree_(std::make_unique<detail::Tree>(config)),
      clearing_(config.clearing.enabled ? std::make_unique<detail::ClearingState>() : nullptr) {}
EgoOctree::EgoOctree(std::unique_ptr<detail::Tree> tree, std::unique_ptr<detail::ClearingState> clearing)
    : tree_(std::move(tree)), clearing_(std::move(clearing)) {}
EgoOctree::~EgoOctree() = default;
EgoOctree::EgoOctree(EgoOctree&&) noexcept = default;
EgoOctree& EgoOctree::operator=(EgoOctree&&) noexcept = default;

std::size_t EgoOctree::size() const { return tree_->size(); }

const UpdateStats& EgoOctree::last_update() const { return last_update_; }
const Config& EgoOctree::config() const { return tree_->config(); }
const Eigen::Isometry3d& EgoOctree::pose() const { return tree_->motion().pose; }
std::uint32_t EgoOctree::frame_count() const { return tree_->motion().frame; }
Eigen::Vector3d EgoOctree::precision_origin() const { return tree_->motion().anchor; }
double EgoOctree::time_origin() const { return tree_->motion().clock.seconds(0.0f); }

Eigen::AlignedBox3d EgoOctree::ego_box() const {
  if (tree_->motion().frame == 0) return Eigen::AlignedBox3d();  // empty
  const detail::Box b = tree_->motion().box;
  const Eigen::Vector3d anchor = tree_->motion().anchor;
  return {Eigen::Vector3d(b.lo[0], b.lo[1], b.lo[2]) + anchor, Eigen::Vector3d(b.hi[0], b.hi[1], b.hi[2]) + anchor};
}

void EgoOctree::for_each_point(const std::function<void(const Eigen::Vector3d&)>& visit) const {
  detail::for_each_held(*tree_, visit);
}

std::vector<Eigen::Vector3d> EgoOctree::points() const {
  std::vector<Eigen::Vector3d> out;
  out.reserve(size());
  for_each_point([&](const Eigen::Vector3d& p) { out.push_back(p); });
  return out;
}

std::vector<HeldPoint> EgoOctree::points_with_attributes() const { return detail::held_points(*tree_); }

Stats EgoOctree::stats() const {
  Stats s = detail::tree_stats(*tree_);
  if (clearing_) s.bytes += clearing_->bytes();
  return s;
}

// --- save and load (src/persist) --------------------------------------------------------------

void EgoOctree::save(const std::string& path) const {
  detail::write_replacing(path, detail::encode_map(*tree_, clearing_.get()));
}

EgoOctree EgoOctree::load(const std::string& path) {
  const std::string bytes = detail::read_whole_file(path);
  try {
    detail::DecodedMap map = detail::decode_map(bytes);
    return EgoOctree(std::move(map.tree), std::move(map.clearing));
  } catch (const detail::ByteError& e) {
    throw std::runtime_error(path + ": byte " + std::to_string(e.offset) + ": " + e.what());
  }
}

// --- the update (src/update) ------------------------------------------------------------------

const UpdateStats& EgoOctree::update(const Eigen::Isometry3d& world_T_sensor, ScanView scan) {
  last_update_ = detail::run_update(*tree_, clearing_.get(), world_T_sensor, scan);
  return last_update_;
}

const UpdateStats& EgoOctree::update_relative(const Eigen::Isometry3d& previous_T_current, ScanView scan) {
  detail::check_pose(previous_T_current, "previous_T_current");
  return update(tree_->motion().pose * previous_T_current, scan);
}

// --- queries (src/query) ----------------------------------------------------------------------

std::size_t EgoOctree::knn(const Eigen::Vector3d& query, std::span<Neighbor> out, Frame frame) const {
  return detail::knn_query(*tree_, query, out, frame);
}

std::vector<Neighbor> EgoOctree::knn(const Eigen::Vector3d& query, std::size_t k, Frame frame) const {
  std::vector<Neighbor> out(std::min<std::size_t>(k, size()));
  out.resize(knn(query, std::span<Neighbor>(out), frame));
  return out;
}

std::size_t EgoOctree::knn(const Eigen::Vector3d& query, std::span<std::uint32_t> ids, std::span<double> sq_dists,
                          Frame frame) const {
  return detail::knn_ids_query(*tree_, query, ids, sq_dists, frame);
}

std::vector<Neighbor> EgoOctree::radius(const Eigen::Vector3d& query, double radius, Frame frame) const {
  return detail::radius_query(*tree_, query, radius, frame);
}

std::vector<Eigen::Vector3d> EgoOctree::box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, Frame frame) const {
  return detail::box_query(*tree_, lo, hi, frame);
}

std::vector<HeldPoint> EgoOctree::box_with_attributes(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                                                     Frame frame) const {
  return detail::box_held_query(*tree_, lo, hi, frame);
}

std::vector<VoxelKey> EgoOctree::voxel_keys(double resolution) const {
  return detail::voxel_keys_of(*tree_, resolution);
}

std::vector<Eigen::Vector3d> EgoOctree::voxelize(double resolution, Frame frame) const {
  const std::vector<VoxelKey> keys = voxel_keys(resolution);
  const Eigen::Vector3d shift = frame == Frame::Ego ? Eigen::Vector3d(pose().translation()) : Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> centres;
  centres.reserve(keys.size());
  for (const VoxelKey& k : keys) {
    centres.push_back(Eigen::Vector3d((double(k.x) + 0.5) * resolution, (double(k.y) + 0.5) * resolution,
                                      (double(k.z) + 0.5) * resolution) -
                      shift);
  }
  return centres;
}

std::string EgoOctree::check_invariants() const { return detail::check_tree(*tree_); }

}  // namespace eco
