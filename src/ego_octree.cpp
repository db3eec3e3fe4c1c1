// EgoOctree: construction, snapshots, save and load, the update's entry points. The update is in
// update/; the queries, shared with snapshots, in map_reader.cpp.

#include "clearing/clearing.hpp"
#include "core/tree/invariants.hpp"
#include "core/tree/tree.hpp"
#include "bytes/byte_stream.hpp"
#include "persist/map_codec.hpp"
#include "persist/map_file.hpp"
#include "query/frames.hpp"
#include "query/queries.hpp"
#include "update/stages.hpp"

#include <eco/ego_octree.hpp>

namespace eco {

namespace {

/// The density cap's counts of the points `tree` holds (a map loaded); null while the cap is off.
std::unique_ptr<detail::DensityCells> counted_density(const detail::Tree& tree) {
  std::unique_ptr<detail::DensityCells> density = detail::density_cells_for(tree.config());
  if (density && tree.root() != detail::kNone) {
    density->enter(tree.motion());
    density->recount([&](auto&& add) {
      detail::walk_leaves(tree, tree.root(), [](const detail::Aabb&) { return 2; },
                          [&](const detail::StoredPoint& s, bool) { add(s.p); });
    });
  }
  return density;
}

}  // namespace

EgoOctree::EgoOctree(const Config& config)
    : tree_(std::make_unique<detail::Tree>(config)),
      clearing_(config.clearing.enabled ? std::make_unique<detail::ClearingState>() : nullptr),
      density_(detail::density_cells_for(config)) {}
EgoOctree::EgoOctree(std::unique_ptr<detail::Tree> tree, std::unique_ptr<detail::ClearingState> clearing)
    : tree_(std::move(tree)), clearing_(std::move(clearing)), density_(counted_density(*tree_)) {}
EgoOctree::~EgoOctree() = default;
EgoOctree::EgoOctree(EgoOctree&&) noexcept = default;
EgoOctree& EgoOctree::operator=(EgoOctree&&) noexcept = default;

const UpdateStats& EgoOctree::last_update() const { return last_update_; }
const detail::Tree& EgoOctree::held() const { return *tree_; }
std::size_t EgoOctree::bytes_beside_tree() const {
  return (clearing_ ? clearing_->bytes() : 0) + (density_ ? density_->bytes() : 0);
}

std::shared_ptr<const Snapshot> EgoOctree::snapshot() {
  return std::shared_ptr<const Snapshot>(new Snapshot(tree_->share()));
}

// --- save and load (src/persist) --------------------------------------------------------------

void EgoOctree::save(const std::string& path) const {
  detail::write_replacing(path, detail::encode_map(*tree_, clearing_.get()));
}

EgoOctree EgoOctree::load(const std::string& path) {
  const detail::FileBytes bytes = detail::read_whole_file(path);
  try {
    detail::DecodedMap map = detail::decode_map(bytes.view());
    return EgoOctree(std::move(map.tree), std::move(map.clearing));
  } catch (const detail::ByteError& e) {
    throw std::runtime_error(path + ": byte " + std::to_string(e.offset) + ": " + e.what());
  }
}

// --- the update (src/update) ------------------------------------------------------------------

const UpdateStats& EgoOctree::update(const Eigen::Isometry3d& world_T_sensor, ScanView scan) {
  last_update_ = detail::run_update(*tree_, clearing_.get(), density_.get(), world_T_sensor, scan);
  return last_update_;
}

const UpdateStats& EgoOctree::update_relative(const Eigen::Isometry3d& previous_T_current, ScanView scan) {
  detail::check_pose(previous_T_current, "previous_T_current");
  return update(tree_->motion().pose * previous_T_current, scan);
}

}  // namespace eco
