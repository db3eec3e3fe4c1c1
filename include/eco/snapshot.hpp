#pragma once
/// @file snapshot.hpp
/// An immutable view of an EgoOctree as of one frame (EgoOctree::snapshot()).

#include <eco/map_reader.hpp>

#include <memory>

namespace eco {

class EgoOctree;

/// The map as it was when EgoOctree::snapshot() published it. It answers every query of
/// MapReader from any number of threads, unchanged whatever its tree does later; frame_count()
/// and pose() name the frame it shows. It shares the tree's unchanged pages, so it holds only
/// what the tree has since replaced (Stats::snapshot_bytes), given back when its last handle goes.
class Snapshot final : public MapReader {
 public:
  ~Snapshot();
  Snapshot(const Snapshot&) = delete;
  Snapshot& operator=(const Snapshot&) = delete;

 private:
  friend class EgoOctree;
  explicit Snapshot(std::unique_ptr<const detail::Tree> tree);
  [[nodiscard]] const detail::Tree& held() const override;

  std::unique_ptr<const detail::Tree> tree_;
};

}  // namespace eco
