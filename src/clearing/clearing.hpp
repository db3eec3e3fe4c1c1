#pragma once
// Free-space clearing (Config::clearing, off by default): what the module offers the update.
//
// Each update, before re-centring, the held points the new scan sees through leave the tree
// (clear_free_space: the rule in include/eco/config.hpp). With clearing.arrivals, the points an
// update brings in where the scan before theirs saw empty space are held for that one update and
// leave at the start of the next (judges_arrivals and ArrivalCheck, then release_arrivals). What clearing keeps
// between updates — the last two scans' range images, the sensor's tables, the arrivals to
// release — is a ClearingState owned beside the tree, handed to the stages that read or write it.

#include "clearing/pixel_lookup.hpp"
#include "clearing/scan_judge.hpp"
#include "core/geometry/motion.hpp"
#include "core/tree/tree.hpp"

#include <eco/types.hpp>

#include <Eigen/Geometry>

#include <cstdint>
#include <span>
#include <vector>

namespace eco::detail {

/// A scan's range image (clearing/range_image.hpp), with its update's frame and pose.
struct KeptImage {
  std::vector<double> storage;
  std::uint32_t frame = 0;  // 0: none yet
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

/// What clearing keeps between updates, so that no frame pays for fresh pages or computes the
/// sensor's tables again.
struct ClearingState {
  KeptImage image;                   // this update's scan
  KeptImage before;                  // the last update's (clearing.arrivals)
  std::vector<double> pixel_tables;  // the pixel lookup's walls and bins (clearing/pixel_lookup.hpp)
  std::vector<StoredPoint> leaving;  // arrivals into space the scan before saw empty: they leave next update

  /// Bytes held.
  [[nodiscard]] std::size_t bytes() const {
    return (image.storage.capacity() + before.storage.capacity() + pixel_tables.capacity()) * sizeof(double) +
           leaving.capacity() * sizeof(StoredPoint);
  }
};

/// Stage 0, before anything else moves them: the points the last update brought in where the
/// scan before theirs saw empty space leave the tree (and `density`, null while the cap is off),
/// counted as cleared.
void release_arrivals(Tree& tree, DensityCells* density, ClearingState& state, UpdateStats& stats);

/// Stage 2b, after shift-out: takes out of the tree, `displaced` and `density` the held points
/// `scan` sees through, and keeps the scan's range image (the last update's too, with
/// clearing.arrivals).
void clear_free_space(Tree& tree, DensityCells* density, ClearingState& state, const Motion& motion, ScanView scan,
                      std::vector<StoredPoint>& displaced, UpdateStats& stats);

/// Notes, of the points an update brings in, those the last update's scan sees through (from
/// where it was taken), in the state's list of points to leave at the next update.
class ArrivalCheck {
 public:
  ArrivalCheck(const Config& config, ClearingState& state, const Motion& motion);
  /// Judges `batch`, new points about to be inserted (StoredPoints or BarePoints).
  template <class Point>
  void operator()(std::span<const Point> batch);

 private:
  PixelLookup pixels_;
  Judge judge_;
  std::vector<StoredPoint>& leaving_;
};

/// For stage 4, after clear_free_space: whether this update's new points are judged against the
/// last update's scan (an ArrivalCheck): with clearing.arrivals, when that scan was the frame before.
[[nodiscard]] bool judges_arrivals(const Config& config, const ClearingState& state, const Motion& motion);

}  // namespace eco::detail
